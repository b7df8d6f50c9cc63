// Accuracy and time of the ASV classifiers against the training-set size (issue 32; run by
// run_rice_classifier_benchmark.sh). Measures every photograph of a training pool and of a held-out
// set once (as `riceasv measure`) and crops each ok grain as the network sees it, then for each class
// scheme (three classes, six grades), model (rtrees, svm, cnn with its default options), number of
// training dishes per grade and repeat (a seeded choice of dishes) trains as
// `riceasv train` does (train_and_evaluate: validation split, final fit, 5-fold cross-validation) and
// classifies the held-out grains. Writes one CSV row per run:
//   rice_classifier_benchmark POOL_DIR HELD_OUT_DIR PIXEL_POOL_MM PIXEL_HELD_OUT_MM OUT_CSV REPEATS [CNN_REPEATS]
// (CNN_REPEATS, default REPEATS: the network takes seconds where the others take milliseconds).
// Each directory is a `riceasv render` output (its truth.csv gives each photograph's grade).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/io/atomic_file.hpp"
#include "rice/classify/labelled_images.hpp"
#include "rice/classify/train_evaluate.hpp"
#include "rice/classify/trait_features.hpp"
#include "rice/cnn/grain_cnn.hpp"
#include "rice/measure/image_files.hpp"

namespace {

using namespace suite::rice;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Dish {
  int grade = 0;
  std::vector<cv::Mat> features;  // one row per ok grain
  std::vector<cv::Mat> crops;     // the same grains' crops for the network, one row each
};

// Every photograph of a rendered set, measured once; the seconds per photograph go to `seconds`.
std::vector<Dish> measure_set(const std::filesystem::path& dir, double mm_per_px, double& seconds) {
  MeasureOptions o;
  o.mm_per_px = mm_per_px;
  std::vector<Dish> dishes;
  const auto start = Clock::now();
  const OnnxSpec crop = cnn_crop_spec(CnnOptions{});
  for (const auto& image : read_labelled_images(dir / "truth.csv").images) {
    Dish d{image.grade, {}, {}};
    const cv::Mat grey = read_grey(image.path);
    const auto measured = measure_grains(grey, o);
    for (const auto& g : measured.grains)
      if (g.ok) {
        d.features.push_back(features_of(g));
        d.crops.push_back(crop_for_network(crop, grey, g.x_px, g.y_px, mm_per_px, measured.levels.dish).reshape(1, 1));
      }
    dishes.push_back(std::move(d));
  }
  seconds = since(start) / static_cast<double>(dishes.size());
  return dishes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7 && argc != 8) {
    std::fprintf(stderr,
                 "usage: %s POOL_DIR HELD_OUT_DIR PIXEL_POOL_MM PIXEL_HELD_OUT_MM OUT_CSV REPEATS [CNN_REPEATS]\n",
                 argv[0]);
    return 2;
  }
  cv::setNumThreads(1);  // one core, as the times are reported
  double pool_s = 0, held_s = 0;
  const auto pool = measure_set(argv[1], std::stod(argv[3]), pool_s);
  const auto held_out = measure_set(argv[2], std::stod(argv[4]), held_s);
  const int repeats = std::stoi(argv[6]);
  const int cnn_repeats = argc == 8 ? std::stoi(argv[7]) : repeats;
  std::map<int, std::vector<int>> pool_by_grade;  // grade -> dish indices
  for (std::size_t i = 0; i < pool.size(); ++i) pool_by_grade[pool[i].grade].push_back(static_cast<int>(i));
  std::size_t most = pool.size();
  for (const auto& [grade, dishes] : pool_by_grade) most = std::min(most, dishes.size());

  std::string csv = fmt::format(
      "# rice classifier benchmark: pool {} ({:.3f} s per photograph to measure), held-out {} ({:.3f} s per "
      "photograph); times in s on one core; accuracy on the held-out ok grains\n"
      "scheme,model,dishes_per_grade,train_grains,repeat,held_out_grains,held_out_accuracy,test_accuracy,"
      "cv_accuracy,train_evaluate_s,fit_s,predict_s_per_grain\n",
      std::filesystem::path(argv[1]).filename().string(), pool_s, std::filesystem::path(argv[2]).filename().string(),
      held_s);
  for (const char* scheme : {"three", "grades"}) {
    const AsvClasses classes = AsvClasses::parse(scheme);
    cv::Mat held_features, held_crops;
    std::vector<int> held_labels;
    for (const auto& d : held_out)
      for (std::size_t g = 0; g < d.features.size(); ++g) {
        held_features.push_back(d.features[g]), held_crops.push_back(d.crops[g]);
        held_labels.push_back(classes.class_of(d.grade));
      }
    for (ModelKind kind : {ModelKind::rtrees, ModelKind::svm, ModelKind::cnn})
      for (std::size_t n : {1u, 2u, 3u, 5u}) {
        if (n > most) continue;
        const bool cnn = kind == ModelKind::cnn;
        for (int r = 0; r < (cnn ? cnn_repeats : repeats); ++r) {
          // The same seeded choice of n dishes of every grade for every model and scheme.
          std::mt19937_64 rng(1000 + 17 * n + static_cast<std::uint64_t>(r));
          cv::Mat samples;
          std::vector<int> labels;
          for (auto [grade, dishes] : pool_by_grade) {
            for (std::size_t i = dishes.size(); i > 1; --i) std::swap(dishes[i - 1], dishes[rng() % i]);
            for (std::size_t k = 0; k < n; ++k) {
              const Dish& d = pool[static_cast<std::size_t>(dishes[k])];
              for (const auto& row : cnn ? d.crops : d.features)
                samples.push_back(row), labels.push_back(classes.class_of(grade));
            }
          }
          TrainOptions o;
          o.classes = classes;
          o.model.kind = kind;
          o.seed = static_cast<std::uint64_t>(r + 1);
          const auto start = Clock::now();
          const Evaluation e = train_and_evaluate(samples, labels, o, *make_learner(o));
          const double train_s = since(start);
          const cv::Mat& held = cnn ? held_crops : held_features;
          const auto predicted_at = Clock::now();
          const auto predictions = e.model->predict(held);
          const double predict_s = since(predicted_at) / held.rows;
          Confusion judged(classes.names);
          for (std::size_t i = 0; i < predictions.size(); ++i) judged.add(held_labels[i], predictions[i].label);
          csv += fmt::format("{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.5f},{:.5f},{:.3e}\n", scheme, to_string(kind),
                             n, samples.rows, r, judged.total(), judged.accuracy(), e.test.accuracy(),
                             e.cross_validation.accuracy(), train_s, e.fit_seconds, predict_s);
          std::fprintf(stderr, "%s %s %zu dishes/grade, repeat %d: held-out %.3f, train+evaluate %.3f s\n", scheme,
                       to_string(kind).c_str(), n, r, judged.accuracy(), train_s);
        }
      }
  }
  suite::io::write_file_atomic(argv[5], csv);
  return 0;
}
