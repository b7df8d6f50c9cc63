#include "rice/classify/train_classifier.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "rice/classify/confusion_chart.hpp"
#include "rice/classify/labelled_images.hpp"
#include "rice/classify/trait_features.hpp"
#include "rice/measure/image_files.hpp"
#include "rice/measure/measure_images.hpp"

namespace suite::rice {
namespace {

struct Sample {
  const ResultRow* row;
  int grade, label;
  int used = -1;  // row of the feature matrix, -1: not trained on
};

nlohmann::json finite(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

std::string set_of(const Evaluation& e, int used) {
  auto holds = [used](const std::vector<int>& v) { return std::find(v.begin(), v.end(), used) != v.end(); };
  if (holds(e.split.test)) return "test";
  if (holds(e.split.validation)) return "validation";
  return "train";
}

void write_samples(const std::filesystem::path& file, const std::vector<Sample>& samples, const Evaluation& e,
                   const AsvClasses& classes) {
  std::string text =
      "# riceasv train: every measured grain of the labelled images; set: train, validation, test or excluded "
      "(flagged grains); test_predicted: the final model's class (test grains); cv_predicted and cv_share: the "
      "class its k-fold model gave it and that model's vote share\n"
      "image,grain,grade,class,status,quality,set,fold,test_predicted,cv_predicted,cv_share\n";
  auto name = [&](int label) { return label >= 0 ? classes.names[static_cast<std::size_t>(label)] : std::string(); };
  for (const auto& s : samples) {
    const auto& g = s.row->traits;
    if (s.used < 0) {
      text += fmt::format("{},{},{},{},{},{},excluded,,,,\n", io::csv_field(s.row->image), g.grain, s.grade,
                          name(s.label), s.row->status, io::csv_field(g.quality));
      continue;
    }
    const auto u = static_cast<std::size_t>(s.used);
    const Prediction& cv = e.cv_predicted[u];
    text += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", io::csv_field(s.row->image), g.grain, s.grade,
                        name(s.label), s.row->status, io::csv_field(g.quality), set_of(e, s.used),
                        e.fold[u] >= 0 ? std::to_string(e.fold[u]) : "", name(e.test_predicted[u]), name(cv.label),
                        cv.label >= 0 && std::isfinite(cv.share) ? fmt::format("{:.3f}", cv.share) : "");
  }
  io::write_file_atomic(file, text);
}

// The network's input for each ok grain (`used` rows, in order): its crop as one CV_8U row.
cv::Mat crops_of(const std::vector<Sample>& samples, const OnnxSpec& spec, double mm_per_px) {
  cv::Mat crops;
  std::string open;
  cv::Mat image;
  for (const auto& s : samples) {
    if (s.used < 0) continue;
    if (s.row->image != open) image = read_for_network(open = s.row->image, spec.channels);
    const auto& g = s.row->traits;
    crops.push_back(crop_for_network(spec, image, g.x_px, g.y_px, mm_per_px, s.row->levels.dish).reshape(1, 1));
  }
  return crops;
}

}  // namespace

TrainSummary train_classifier(const std::filesystem::path& labels, const TrainOptions& options,
                              const MeasureOptions& measure, const std::filesystem::path& out, Logger& log) {
  const LabelledSet set = read_labelled_images(labels);
  TrainSummary summary;
  summary.problems = set.problems;
  for (const auto& p : set.problems) log.info("{}", p);  // the closing error repeats the first
  summary.images = static_cast<int>(set.images.size());
  if (set.images.empty())
    throw InputError(fmt::format("labels '{}': no labelled images to train on ({})", labels.string(),
                                 set.problems.empty() ? "none listed" : set.problems.front()));

  // The learner first: a pretrained network that cannot be used stops before any photograph is read.
  const auto learner = make_learner(options);

  // Measure every labelled image, as `riceasv measure` does.
  std::vector<std::filesystem::path> paths;
  std::map<std::string, int> grade_of;
  for (const auto& image : set.images) {
    paths.push_back(image.path);
    grade_of[image.path.string()] = image.grade;
  }
  const auto measure_start = std::chrono::steady_clock::now();
  const auto rows = measure_images(paths, measure, out / "measured", false, log);
  const double measure_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count();

  // Ok grains become features; flagged ones are counted by reason; failed images are problems.
  std::vector<Sample> samples;
  cv::Mat features;
  std::vector<int> used_labels;
  std::map<std::string, int> excluded_by_reason;
  nlohmann::json failed = nlohmann::json::array();
  for (const auto& r : rows) {
    if (r.status == "failed") {
      summary.problems.push_back(r.message);
      failed.push_back({{"image", r.image}, {"message", r.message}});
      continue;
    }
    const int grade = grade_of.at(r.image);
    Sample s{&r, grade, options.classes.class_of(grade)};
    if (r.status == "ok") {
      s.used = features.rows;
      features.push_back(features_of(r.traits));
      used_labels.push_back(s.label);
    } else {
      ++summary.grains_excluded;
      excluded_by_reason[r.traits.quality] += 1;
    }
    samples.push_back(s);
  }
  summary.grains_used = features.rows;
  if (features.rows == 0)
    throw InputError(
        fmt::format("labels '{}': no ok grain in {} image(s) to train on ({} flagged, {} image(s) "
                    "failed); check the photographs and --pixel-size",
                    labels.string(), set.images.size(), summary.grains_excluded, failed.size()));
  if (summary.grains_excluded > 0)
    log.info("{} flagged grain(s) not trained on (touching or cut by the frame)", summary.grains_excluded);

  // A network learns from each ok grain's crop, the others from its features.
  double crop_seconds = 0;
  cv::Mat samples_matrix = features;
  if (const OnnxSpec* crop = learner->crop_spec()) {
    const auto crop_start = std::chrono::steady_clock::now();
    samples_matrix = crops_of(samples, *crop, measure.mm_per_px);
    crop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - crop_start).count();
  }
  const Evaluation e = train_and_evaluate(samples_matrix, used_labels, options, *learner);
  summary.test_accuracy = e.test.accuracy();
  summary.cv_accuracy = e.cross_validation.accuracy();

  // Reports and the model.
  nlohmann::json per_class = nlohmann::json::object();
  for (int c = 0; c < options.classes.count(); ++c)
    per_class[options.classes.names[static_cast<std::size_t>(c)]] = {
        {"grades", options.classes.grades_of(c)}, {"grains", std::count(used_labels.begin(), used_labels.end(), c)}};
  nlohmann::json cv = {{"folds", options.folds}};
  if (options.folds > 0) {
    const double mean = std::accumulate(e.fold_accuracy.begin(), e.fold_accuracy.end(), 0.0) / options.folds;
    double var = 0;
    for (double a : e.fold_accuracy) var += (a - mean) * (a - mean);
    cv["fold_accuracy"] = e.fold_accuracy;
    cv["mean_accuracy"] = mean;
    cv["sd_accuracy"] = options.folds > 1 ? std::sqrt(var / (options.folds - 1)) : 0.0;
    cv["pooled"] = e.cross_validation.to_json();
  }
  const nlohmann::json evaluation = {{"program", "riceasv train"},
                                     {"labels", labels.string()},
                                     {"layout", set.layout},
                                     {"pixel_size_mm", measure.mm_per_px},
                                     {"classes", options.classes.scheme},
                                     {"model", to_string(options.model.kind)},
                                     {"seed", options.seed},
                                     {"shares",
                                      {{"train", 1 - options.validation_share - options.test_share},
                                       {"validation", options.validation_share},
                                       {"test", options.test_share}}},
                                     {"images", {{"labelled", set.images.size()}, {"failed", failed}}},
                                     {"problems", summary.problems},
                                     {"grains",
                                      {{"used", summary.grains_used},
                                       {"excluded_flagged", summary.grains_excluded},
                                       {"excluded_by_reason", excluded_by_reason},
                                       {"per_class", per_class},
                                       {"train", e.split.train.size()},
                                       {"validation", e.split.validation.size()},
                                       {"test", e.split.test.size()}}},
                                     {"selection", e.selection},
                                     {"validation", e.validation.to_json()},
                                     {"test", e.test.to_json()},
                                     {"cross_validation", cv},
                                     {"times_s",
                                      {{"measure", measure_seconds},
                                       {"crop", crop_seconds},
                                       {"fit_final_model", e.fit_seconds},
                                       {"predict_per_grain", e.predict_seconds_per_grain}}}};
  e.model->save(out, {{"labels", labels.string()},
                      {"pixel_size_mm", measure.mm_per_px},
                      {"grains", summary.grains_used + 0},
                      {"fitted_on", e.split.train.size() + e.split.validation.size()},
                      {"test_accuracy", finite(summary.test_accuracy)},
                      {"cv_accuracy", finite(summary.cv_accuracy)},
                      {"evaluation", "evaluation.json"}});
  io::write_file_atomic(out / "evaluation.json", evaluation.dump(2) + "\n");
  io::write_file_atomic(out / "confusion_test.csv", e.test.to_csv());
  std::vector<ConfusionPanel> panels = {{"test split", e.test}};
  if (options.folds > 0) {
    io::write_file_atomic(out / "confusion_cv.csv", e.cross_validation.to_csv());
    panels.push_back({fmt::format("{}-fold cross-validation", options.folds), e.cross_validation});
  }
  draw_confusion_chart(out / "confusion.png", panels);
  write_samples(out / "samples.csv", samples, e, options.classes);
  log.info(
      "{} grains ({} flagged not used) from {} images; test accuracy {:.1f}% ({} grains), {}-fold {:.1f}%; "
      "model in {}",
      summary.grains_used, summary.grains_excluded, set.images.size(), 100 * summary.test_accuracy, e.test.total(),
      options.folds, 100 * summary.cv_accuracy, out.string());
  return summary;
}

}  // namespace suite::rice
