#include "rice/classify/classify_images.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "rice/classify/trait_classifier.hpp"
#include "rice/classify/trait_features.hpp"
#include "rice/measure/measure_images.hpp"

namespace suite::rice {

ClassifySummary classify_images(const std::vector<std::filesystem::path>& targets,
                                const std::filesystem::path& model_dir, const MeasureOptions& measure,
                                const std::filesystem::path& out, Logger& log) {
  const TraitClassifier model = TraitClassifier::load(model_dir);
  const AsvClasses& classes = model.classes();
  const auto rows = measure_images(targets, measure, out, false, log);

  // One prediction per measured grain (ok or flagged), in the rows' order.
  cv::Mat features;
  for (const auto& r : rows)
    if (r.status != "failed") features.push_back(features_of(r.traits));
  const auto start = std::chrono::steady_clock::now();
  const auto predictions = model.predict(features);
  const double predict_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  ClassifySummary summary;
  std::string text = fmt::format(
      "# riceasv classify with model '{}' ({}, classes {}): class and vote share (the share of the forest's trees "
      "that voted for it; empty for svm) per grain; flagged grains' classes are not to be trusted\n"
      "image,grain,x_px,y_px,status,quality,class,share,message\n",
      model_dir.string(), to_string(model.options().kind), classes.scheme);
  std::vector<long> counts(static_cast<std::size_t>(classes.count()), 0);
  nlohmann::json images = nlohmann::json::array();
  std::map<std::string, std::vector<long>> per_image;
  std::vector<std::string> image_order;
  std::set<std::string> failed;
  std::size_t next = 0;
  for (const auto& r : rows) {
    if (per_image.find(r.image) == per_image.end()) {
      image_order.push_back(r.image);
      per_image[r.image] = std::vector<long>(static_cast<std::size_t>(classes.count()), 0);
      ++summary.images;
    }
    if (r.status == "failed") {
      ++summary.failed_images;
      if (summary.first_failure.empty()) summary.first_failure = r.message;
      text += fmt::format("{},0,,,failed,,,,{}\n", io::csv_field(r.image), io::csv_field(r.message));
      images.push_back({{"image", r.image}, {"failed", r.message}});
      failed.insert(r.image);
      continue;
    }
    const Prediction& p = predictions[next++];
    const std::string& name = classes.names[static_cast<std::size_t>(p.label)];
    const auto& g = r.traits;
    text += fmt::format("{},{},{:.1f},{:.1f},{},{},{},{},\n", io::csv_field(r.image), g.grain, g.x_px, g.y_px, r.status,
                        io::csv_field(g.quality), name, std::isfinite(p.share) ? fmt::format("{:.3f}", p.share) : "");
    if (r.status == "ok") {
      ++summary.grains;
      counts[static_cast<std::size_t>(p.label)] += 1;
      per_image[r.image][static_cast<std::size_t>(p.label)] += 1;
    } else {
      ++summary.flagged;
    }
  }
  io::write_file_atomic(out / "classes.csv", text);

  auto by_name = [&](const std::vector<long>& c) {
    nlohmann::json j = nlohmann::json::object();
    for (int k = 0; k < classes.count(); ++k)
      j[classes.names[static_cast<std::size_t>(k)]] = c[static_cast<std::size_t>(k)];
    return j;
  };
  for (const auto& image : image_order) {
    const auto& c = per_image[image];
    long total = 0;
    for (long n : c) total += n;
    if (failed.count(image)) continue;  // listed above with its reason
    const auto most = std::max_element(c.begin(), c.end()) - c.begin();
    images.push_back({{"image", image},
                      {"grains_ok", total},
                      {"counts", by_name(c)},
                      {"most_frequent", total > 0 ? nlohmann::json(classes.names[static_cast<std::size_t>(most)])
                                                  : nlohmann::json(nullptr)}});
  }
  const nlohmann::json record = {
      {"program", "riceasv classify"},
      {"model", model_dir.string()},
      {"model_type", to_string(model.options().kind)},
      {"classes", classes.names},
      {"pixel_size_mm", measure.mm_per_px},
      {"grains_ok", summary.grains},
      {"grains_flagged", summary.flagged},
      {"images_failed", summary.failed_images},
      {"counts", by_name(counts)},
      {"images", images},
      {"predict_seconds_per_grain", features.rows > 0 ? predict_seconds / features.rows : 0.0}};
  io::write_file_atomic(out / "classify.json", record.dump(2) + "\n");
  return summary;
}

}  // namespace suite::rice
