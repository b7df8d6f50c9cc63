#include "rice/classify/train_evaluate.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "core/errors.hpp"

namespace suite::rice {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<int> labels_of(const std::vector<int>& labels, const std::vector<int>& rows) {
  std::vector<int> out;
  for (int r : rows) out.push_back(labels[static_cast<std::size_t>(r)]);
  return out;
}

Confusion judge(const TraitClassifier& model, const cv::Mat& features, const std::vector<int>& labels,
                const std::vector<int>& rows, const AsvClasses& classes, std::vector<int>* predicted = nullptr) {
  Confusion confusion(classes.names);
  const auto predictions = model.predict(select_rows(features, rows));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    confusion.add(labels[static_cast<std::size_t>(rows[i])], predictions[i].label);
    if (predicted) (*predicted)[static_cast<std::size_t>(rows[i])] = predictions[i].label;
  }
  return confusion;
}

}  // namespace

cv::Mat select_rows(const cv::Mat& features, const std::vector<int>& rows) {
  cv::Mat out(static_cast<int>(rows.size()), features.cols, features.type());
  for (std::size_t i = 0; i < rows.size(); ++i) features.row(rows[i]).copyTo(out.row(static_cast<int>(i)));
  return out;
}

Evaluation train_and_evaluate(const cv::Mat& features, const std::vector<int>& labels, const TrainOptions& options) {
  const AsvClasses& classes = options.classes;
  std::vector<long> per_class(static_cast<std::size_t>(classes.count()), 0);
  for (int l : labels) per_class.at(static_cast<std::size_t>(l)) += 1;
  for (int c = 0; c < classes.count(); ++c)
    if (per_class[static_cast<std::size_t>(c)] == 0)
      throw InputError(
          fmt::format("class '{}' (grade {}) has no usable grain to train on; add labelled photographs "
                      "of grade {} (flagged grains, touching or cut by the frame, are not used)",
                      classes.names[static_cast<std::size_t>(c)], classes.grades_of(c), classes.grades_of(c)));
  const int n = static_cast<int>(labels.size());
  ModelOptions model = options.model;
  model.seed = options.seed;

  // 1. The split.
  const Split split = stratified_split(labels, options.validation_share, options.test_share, options.seed);
  nlohmann::json selection = {{"by", "validation accuracy"}};

  // 2. The forest's depth on the validation grains.
  Confusion validation(classes.names);
  if (model.kind == ModelKind::rtrees && !split.validation.empty()) {
    const cv::Mat train = select_rows(features, split.train);
    double best = -1;
    int best_depth = model.max_depth;
    for (int depth : {4, 8, 16}) {
      ModelOptions trial = model;
      trial.max_depth = depth;
      const auto fitted = TraitClassifier::fit(train, labels_of(labels, split.train), classes, trial);
      Confusion c = judge(fitted, features, labels, split.validation, classes);
      selection["tried"].push_back({{"max_depth", depth}, {"validation_accuracy", c.accuracy()}});
      if (c.accuracy() > best) best = c.accuracy(), best_depth = depth, validation = c;
    }
    model.max_depth = best_depth;
    selection["max_depth"] = best_depth;
  } else {
    selection["by"] = model.kind == ModelKind::svm ? "OpenCV trainAuto (C, gamma; 5-fold on the training grains)"
                                                   : "none: no validation grains, the default depth";
  }

  // 3. The final model on train + validation, judged on the test grains.
  std::vector<int> fit_rows = split.train;
  fit_rows.insert(fit_rows.end(), split.validation.begin(), split.validation.end());
  const auto start = std::chrono::steady_clock::now();
  TraitClassifier final_model =
      TraitClassifier::fit(select_rows(features, fit_rows), labels_of(labels, fit_rows), classes, model);
  Evaluation e{std::move(final_model),
               split,
               selection,
               validation,
               Confusion(classes.names),
               Confusion(classes.names),
               {},
               std::vector<int>(static_cast<std::size_t>(n), -1),
               std::vector<Prediction>(static_cast<std::size_t>(n)),
               std::vector<int>(static_cast<std::size_t>(n), -1),
               seconds_since(start),
               0};
  if (model.kind == ModelKind::svm && !split.validation.empty())
    e.validation = judge(e.model, features, labels, split.validation, classes);  // seen in the fit: for reference
  e.test = judge(e.model, features, labels, split.test, classes, &e.test_predicted);
  const auto timed = std::chrono::steady_clock::now();
  (void)e.model.predict(features);
  e.predict_seconds_per_grain = n > 0 ? seconds_since(timed) / n : 0;

  // 4. k-fold cross-validation with the chosen parameters.
  if (options.folds > 0) {
    e.fold = stratified_folds(labels, options.folds, options.seed);
    for (int f = 0; f < options.folds; ++f) {
      std::vector<int> in, out;
      for (int i = 0; i < n; ++i) (e.fold[static_cast<std::size_t>(i)] == f ? out : in).push_back(i);
      const auto fitted = TraitClassifier::fit(select_rows(features, in), labels_of(labels, in), classes, model);
      const auto predictions = fitted.predict(select_rows(features, out));
      Confusion c(classes.names);
      for (std::size_t i = 0; i < out.size(); ++i) {
        c.add(labels[static_cast<std::size_t>(out[i])], predictions[i].label);
        e.cv_predicted[static_cast<std::size_t>(out[i])] = predictions[i];
      }
      e.fold_accuracy.push_back(c.accuracy());
      e.cross_validation.add(c);
    }
  }
  return e;
}

}  // namespace suite::rice
