#include "rice/classify/classify_images.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "rice/classify/onnx_classifier.hpp"
#include "rice/classify/trait_classifier.hpp"
#include "rice/classify/trait_features.hpp"
#include "rice/cnn/grain_cnn.hpp"
#include "rice/cnn/pretrained_net.hpp"
#include "rice/measure/image_files.hpp"
#include "rice/measure/measure_images.hpp"

namespace suite::rice {

namespace {

// classes.csv and classify.json from the measured rows and one prediction per row that is not
// failed, in the rows' order. `header` is the '#' line of classes.csv; `record` gets the counts.
ClassifySummary write_classification(const std::vector<ResultRow>& rows, const std::vector<Prediction>& predictions,
                                     const std::vector<std::string>& names, const std::string& header,
                                     nlohmann::json record, const std::filesystem::path& out) {
  const std::size_t n_classes = names.size();
  ClassifySummary summary;
  std::string text = header + "\nimage,grain,x_px,y_px,status,quality,class,share,message\n";
  std::vector<long> counts(n_classes, 0);
  nlohmann::json images = nlohmann::json::array();
  std::map<std::string, std::vector<long>> per_image;
  std::vector<std::string> image_order;
  std::set<std::string> failed;
  std::size_t next = 0;
  for (const auto& r : rows) {
    if (per_image.find(r.image) == per_image.end()) {
      image_order.push_back(r.image);
      per_image[r.image] = std::vector<long>(n_classes, 0);
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
    const Prediction& p = predictions.at(next++);
    const std::string& name = names[static_cast<std::size_t>(p.label)];
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
    for (std::size_t k = 0; k < n_classes; ++k) j[names[k]] = c[k];
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
                      {"most_frequent",
                       total > 0 ? nlohmann::json(names[static_cast<std::size_t>(most)]) : nlohmann::json(nullptr)}});
  }
  record["classes"] = names;
  record["grains_ok"] = summary.grains;
  record["grains_flagged"] = summary.flagged;
  record["images_failed"] = summary.failed_images;
  record["counts"] = by_name(counts);
  record["images"] = images;
  io::write_file_atomic(out / "classify.json", record.dump(2) + "\n");
  return summary;
}

// A network that scores crops around the grains: a user's ONNX network or the suite's own CNN.
struct CropNetwork {
  OnnxSpec spec;                                              // the crop and the classes
  std::function<std::vector<double>(const cv::Mat&)> scores;  // probabilities of one crop
  std::string name;                                           // "ONNX network 'x.onnx'", "network 'DIR'"
  nlohmann::json record;                                      // classify.json's description of the model
};

// Measures the images, crops every measured grain by the network's crop rule, scores it and writes
// classes.csv, scores.csv, classify.json (and crops/ with `write_crops`). A photograph whose grains
// cannot all be scored becomes a failed row; the others are kept.
ClassifySummary classify_crops(const std::vector<std::filesystem::path>& targets, const CropNetwork& net,
                               const MeasureOptions& measure, const std::filesystem::path& out, bool write_crops,
                               Logger& log) {
  const OnnxSpec& spec = net.spec;
  const auto measured = measure_images(targets, measure, out, false, log);
  if (write_crops) std::filesystem::create_directories(out / "crops");

  std::string scores = fmt::format(
      "# riceasv classify with {}: each class's score (probability) per grain; crop_x0, crop_y0: "
      "the crop's top-left pixel in the photograph, crop_px its side ({} mm)\nimage,grain,status,crop_x0,crop_y0,"
      "crop_px",
      net.name, spec.crop_mm);
  for (const auto& c : spec.classes) scores += ",score_" + c;
  scores += "\n";
  std::vector<ResultRow> rows;
  std::vector<Prediction> predictions;
  double forward_seconds = 0;
  bool changed = false;
  for (std::size_t i = 0; i < measured.size();) {
    std::size_t j = i;
    while (j < measured.size() && measured[j].image == measured[i].image) ++j;
    const std::string& name = measured[i].image;
    if (measured[i].status == "failed") {
      rows.push_back(measured[i]);
      i = j;
      continue;
    }
    // This photograph's grains; committed only when every one of them ran.
    std::vector<Prediction> here;
    std::string lines;
    try {
      const cv::Mat image = read_for_network(name, spec.channels);
      for (std::size_t k = i; k < j; ++k) {
        const ResultRow& r = measured[k];
        cv::Rect region;
        const cv::Mat crop =
            crop_for_network(spec, image, r.traits.x_px, r.traits.y_px, measure.mm_per_px, r.levels.dish, &region);
        const auto start = std::chrono::steady_clock::now();
        const std::vector<double> s = net.scores(crop);
        forward_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto best = std::max_element(s.begin(), s.end()) - s.begin();
        here.push_back({static_cast<int>(best), s[static_cast<std::size_t>(best)]});
        lines += fmt::format("{},{},{},{},{},{}", io::csv_field(name), r.traits.grain, r.status, region.x, region.y,
                             region.width);
        for (double v : s) lines += fmt::format(",{:.9g}", v);
        lines += "\n";
        if (write_crops) {
          cv::Mat png = crop;
          if (spec.channels == 3 && spec.rgb) cv::cvtColor(crop, png, cv::COLOR_RGB2BGR);
          write_png(
              out / "crops" / fmt::format("{}_g{}.png", std::filesystem::path(name).stem().string(), r.traits.grain),
              png);
        }
      }
    } catch (const InputError& e) {
      rows.push_back(ResultRow::failed(name, e.what()));
      changed = true;
      i = j;
      continue;
    } catch (const cv::Exception& e) {
      rows.push_back(ResultRow::failed(
          name, fmt::format("the {} failed on a grain of '{}' ({}); check the network with a crop from --crops",
                            net.name, name, e.err)));
      changed = true;
      i = j;
      continue;
    }
    rows.insert(rows.end(), measured.begin() + static_cast<std::ptrdiff_t>(i),
                measured.begin() + static_cast<std::ptrdiff_t>(j));
    predictions.insert(predictions.end(), here.begin(), here.end());
    scores += lines;
    i = j;
  }
  if (changed) write_results(out / "results.csv", rows, measure.mm_per_px);
  io::write_file_atomic(out / "scores.csv", scores);

  const std::string header = fmt::format(
      "# riceasv classify with {} (classes {}): class and its score (the network's probability) "
      "per grain; flagged grains' classes are not to be trusted",
      net.name, fmt::join(spec.classes, " "));
  nlohmann::json record = net.record;
  record["program"] = "riceasv classify";
  record["input"] = {{"width", spec.width}, {"height", spec.height}, {"channels", spec.channels}};
  record["crop_mm"] = spec.crop_mm;
  record["pixel_size_mm"] = measure.mm_per_px;
  record["predict_seconds_per_grain"] = predictions.empty() ? 0.0 : forward_seconds / predictions.size();
  return write_classification(rows, predictions, spec.classes, header, record, out);
}

}  // namespace

ClassifySummary classify_images(const std::vector<std::filesystem::path>& targets,
                                const std::filesystem::path& model_dir, const MeasureOptions& measure,
                                const std::filesystem::path& out, bool write_crops, Logger& log) {
  // A network (the suite's or a fine-tuned one) runs on crops, as an ONNX network does.
  const auto run_network = [&](const auto& net, const char* what, const char* type) {
    const CropNetwork crop_network{net.spec(),
                                   [&net](const cv::Mat& crop) { return net.scores(crop); },
                                   fmt::format("{} '{}'", what, model_dir.string()),
                                   {{"model", model_dir.string()}, {"model_type", type}}};
    return classify_crops(targets, crop_network, measure, out, write_crops, log);
  };
  if (PretrainedClassifier::is_pretrained_model(model_dir))
    return run_network(PretrainedClassifier::load(model_dir), "fine-tuned network", "pretrained");
  if (CnnClassifier::is_cnn_model(model_dir)) return run_network(CnnClassifier::load(model_dir), "network", "cnn");
  if (write_crops)
    throw InputError(
        fmt::format("--crops: the model in '{}' classifies traits, not crops; leave --crops out, or give a network",
                    model_dir.string()));
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

  const std::string header = fmt::format(
      "# riceasv classify with model '{}' ({}, classes {}): class and vote share (the share of the forest's trees "
      "that voted for it; empty for svm) per grain; flagged grains' classes are not to be trusted",
      model_dir.string(), to_string(model.options().kind), classes.scheme);
  const nlohmann::json record = {
      {"program", "riceasv classify"},
      {"model", model_dir.string()},
      {"model_type", to_string(model.options().kind)},
      {"pixel_size_mm", measure.mm_per_px},
      {"predict_seconds_per_grain", features.rows > 0 ? predict_seconds / features.rows : 0.0}};
  return write_classification(rows, predictions, classes.names, header, record, out);
}

ClassifySummary classify_images_onnx(const std::vector<std::filesystem::path>& targets,
                                     const std::filesystem::path& onnx, const MeasureOptions& measure,
                                     const std::filesystem::path& out, bool write_crops, Logger& log) {
  const OnnxClassifier net = OnnxClassifier::load(onnx);
  const CropNetwork crop_network{
      net.spec(),
      [&net](const cv::Mat& crop) { return net.scores(crop); },
      fmt::format("ONNX network '{}'", net.files().onnx.string()),
      {{"model", net.files().onnx.string()}, {"model_type", "onnx"}, {"model_description", net.files().json.string()}}};
  return classify_crops(targets, crop_network, measure, out, write_crops, log);
}

}  // namespace suite::rice
