#include "rice/classify/train_evaluate.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "core/errors.hpp"
#include "rice/cnn/pretrained_net.hpp"

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

Confusion judge(const FittedModel& model, const cv::Mat& features, const std::vector<int>& labels,
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

Evaluation train_and_evaluate(const cv::Mat& samples, const std::vector<int>& labels, const TrainOptions& options,
                              Learner& learner) {
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

  // 1. The split.
  Evaluation e;
  e.split = stratified_split(labels, options.validation_share, options.test_share, options.seed);
  e.validation = e.test = e.cross_validation = Confusion(classes.names);
  e.test_predicted.assign(static_cast<std::size_t>(n), -1);
  e.cv_predicted.assign(static_cast<std::size_t>(n), Prediction{});
  e.fold.assign(static_cast<std::size_t>(n), -1);
  const Split& split = e.split;

  // 2. The learner's parameters on the validation grains.
  std::vector<Prediction> validation_predicted;
  e.selection =
      learner.select(select_rows(samples, split.train), labels_of(labels, split.train),
                     select_rows(samples, split.validation), labels_of(labels, split.validation), validation_predicted);
  for (std::size_t i = 0; i < validation_predicted.size(); ++i)
    e.validation.add(labels[static_cast<std::size_t>(split.validation[i])], validation_predicted[i].label);

  // 3. The final model on train + validation, judged on the test grains.
  std::vector<int> fit_rows = split.train;
  fit_rows.insert(fit_rows.end(), split.validation.begin(), split.validation.end());
  const auto start = std::chrono::steady_clock::now();
  e.model = learner.fit(select_rows(samples, fit_rows), labels_of(labels, fit_rows));
  e.fit_seconds = seconds_since(start);
  if (validation_predicted.empty() && !split.validation.empty())
    e.validation = judge(*e.model, samples, labels, split.validation, classes);  // seen in the fit: for reference
  e.test = judge(*e.model, samples, labels, split.test, classes, &e.test_predicted);
  const auto timed = std::chrono::steady_clock::now();
  (void)e.model->predict(samples);
  e.predict_seconds_per_grain = n > 0 ? seconds_since(timed) / n : 0;

  // 4. k-fold cross-validation with the chosen parameters.
  if (options.folds > 0) {
    e.fold = stratified_folds(labels, options.folds, options.seed);
    for (int f = 0; f < options.folds; ++f) {
      std::vector<int> in, out;
      for (int i = 0; i < n; ++i) (e.fold[static_cast<std::size_t>(i)] == f ? out : in).push_back(i);
      const auto fitted = learner.fit(select_rows(samples, in), labels_of(labels, in));
      const auto predictions = fitted->predict(select_rows(samples, out));
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

std::unique_ptr<Learner> make_learner(const TrainOptions& options) {
  CnnOptions cnn = options.cnn;
  cnn.seed = options.seed;
  if (options.model.kind == ModelKind::cnn) return std::make_unique<CnnLearner>(options.classes, cnn);
  if (options.model.kind == ModelKind::pretrained) {
    if (options.pretrained.empty())
      throw InputError(
          "--model-type pretrained needs --pretrained NET (your TorchScript network, net.pt with "
          "net.json beside it; docs/rice.md)");
    return std::make_unique<PretrainedLearner>(
        PretrainedClassifier::load_pretrained(options.pretrained, options.classes), cnn);
  }
  ModelOptions model = options.model;
  model.seed = options.seed;
  return std::make_unique<TraitLearner>(options.classes, model);
}

Evaluation train_and_evaluate(const cv::Mat& features, const std::vector<int>& labels, const TrainOptions& options) {
  if (options.model.kind != ModelKind::rtrees && options.model.kind != ModelKind::svm)
    throw std::logic_error("train_and_evaluate: a network learns from crops; give its learner (make_learner)");
  return train_and_evaluate(features, labels, options, *make_learner(options));
}

}  // namespace suite::rice
