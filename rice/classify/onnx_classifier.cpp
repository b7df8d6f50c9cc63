#include "rice/classify/onnx_classifier.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "core/errors.hpp"
#include "rice/classify/onnx_graph.hpp"

namespace suite::rice {
namespace {

constexpr const char* kFormat = "riceasv onnx classifier";
constexpr const char* kConvention = "docs/rice.md, \"A network of your own (ONNX)\"";

// The first line of an OpenCV error, without the file and line OpenCV puts in front.
std::string opencv_reason(const cv::Exception& e) {
  std::string s = e.err.empty() ? std::string(e.what()) : e.err;
  s = s.substr(0, s.find('\n'));
  return s;
}

void only_keys(const nlohmann::json& j, const std::set<std::string>& allowed, const std::string& where,
               const std::filesystem::path& file) {
  for (const auto& [key, value] : j.items())
    if (!allowed.count(key))
      throw InputError(fmt::format("'{}': unknown key '{}{}'; valid keys there: {} ({})", file.string(), where, key,
                                   fmt::join(allowed, ", "), kConvention));
}

double positive_number(const nlohmann::json& j, const std::string& key, const std::filesystem::path& file) {
  if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() > 0))
    throw InputError(fmt::format("'{}': '{}' must be a number above 0 ({})", file.string(), key, kConvention));
  return j[key].get<double>();
}

std::vector<double> per_channel(const nlohmann::json& j, const std::string& key, int channels, bool positive,
                                const std::filesystem::path& file) {
  const bool ok = j.contains(key) && j[key].is_array() && static_cast<int>(j[key].size()) == channels &&
                  std::all_of(j[key].begin(), j[key].end(), [&](const nlohmann::json& v) {
                    return v.is_number() && std::isfinite(v.get<double>()) && (!positive || v.get<double>() > 0);
                  });
  if (!ok)
    throw InputError(fmt::format(
        "'{}': 'normalisation.{}' must be a list of {} number(s){}, one per input channel; the network sees "
        "(pixel / 255 - mean) / std ({})",
        file.string(), key, channels, positive ? " above 0" : "", kConvention));
  return j[key].get<std::vector<double>>();
}

}  // namespace

OnnxFiles onnx_files(const std::filesystem::path& argument) {
  std::error_code ec;
  if (std::filesystem::is_directory(argument, ec)) {
    if (!std::filesystem::exists(argument / "net.onnx", ec)) {
      const bool traits = std::filesystem::exists(argument / "model.json", ec);
      throw InputError(fmt::format(
          "--onnx '{}': the folder holds no net.onnx; give a folder with net.onnx and net.json, or NET.onnx with "
          "NET.json beside it ({}){}",
          argument.string(), kConvention,
          traits ? "; this folder holds a model from 'riceasv train': give it with --model instead" : ""));
    }
    return {argument / "net.onnx", argument / "net.json"};
  }
  if (!std::filesystem::exists(argument, ec))
    throw InputError(fmt::format(
        "--onnx '{}': no such file or folder; give NET.onnx (with NET.json beside it) or a folder holding net.onnx "
        "and net.json",
        argument.string()));
  auto json = argument;
  json.replace_extension(".json");
  return {argument, json};
}

OnnxSpec parse_onnx_spec(const nlohmann::json& j, const std::filesystem::path& file) {
  if (!j.is_object() || j.value("format", "") != kFormat)
    throw InputError(
        fmt::format("'{}' is not a {} description (its format is '{}'); write it with \"format\": \"{}\" "
                    "as {} shows",
                    file.string(), kFormat, j.is_object() ? j.value("format", "none") : "none", kFormat, kConvention));
  only_keys(j, {"format", "version", "description", "classes", "input", "crop_mm", "normalisation", "output"}, "",
            file);
  if (j.value("version", 1) != 1)
    throw InputError(
        fmt::format("'{}': version {}; this riceasv reads version 1", file.string(), j.value("version", 1)));
  OnnxSpec s;
  const bool classes_ok = j.contains("classes") && j["classes"].is_array() && j["classes"].size() >= 2 &&
                          std::all_of(j["classes"].begin(), j["classes"].end(), [](const nlohmann::json& c) {
                            return c.is_string() && !c.get<std::string>().empty() &&
                                   c.get<std::string>().find_first_of(",\"\n") == std::string::npos;
                          });
  if (!classes_ok)
    throw InputError(fmt::format(
        "'{}': 'classes' must be a list of at least two names (no commas or quotes), in the order of the network's "
        "outputs, e.g. [\"low\", \"medium\", \"high\"]",
        file.string()));
  s.classes = j["classes"].get<std::vector<std::string>>();
  if (std::set<std::string>(s.classes.begin(), s.classes.end()).size() != s.classes.size())
    throw InputError(fmt::format("'{}': 'classes' names a class twice: {}", file.string(), fmt::join(s.classes, ", ")));

  if (!j.contains("input") || !j["input"].is_object())
    throw InputError(fmt::format(
        "'{}': 'input' is missing; give {{\"width\": W, \"height\": H, \"channels\": 1 or 3}}, the size the network "
        "was exported with ({})",
        file.string(), kConvention));
  const auto& in = j["input"];
  only_keys(in, {"width", "height", "channels", "colour_order"}, "input.", file);
  auto side = [&](const char* key) {
    if (!in.contains(key) || !in[key].is_number_integer() || in[key].get<int>() < 1 || in[key].get<int>() > 4096)
      throw InputError(
          fmt::format("'{}': 'input.{}' must be a whole number of pixels from 1 to 4096", file.string(), key));
    return in[key].get<int>();
  };
  s.width = side("width");
  s.height = side("height");
  if (!in.contains("channels") || !in["channels"].is_number_integer() ||
      (in["channels"].get<int>() != 1 && in["channels"].get<int>() != 3))
    throw InputError(
        fmt::format("'{}': 'input.channels' must be 1 (the grey photograph) or 3 (its colours, see 'colour_order')",
                    file.string()));
  s.channels = in["channels"].get<int>();
  const std::string order = in.value("colour_order", "rgb");
  if (order != "rgb" && order != "bgr")
    throw InputError(fmt::format("'{}': 'input.colour_order' is '{}'; give 'rgb' (torchvision, Keras) or 'bgr'",
                                 file.string(), order));
  s.rgb = order == "rgb";

  s.crop_mm = positive_number(j, "crop_mm", file);
  if (!j.contains("normalisation") || !j["normalisation"].is_object())
    throw InputError(fmt::format(
        "'{}': 'normalisation' is missing; give {{\"mean\": [...], \"std\": [...]}}, one number per channel: the "
        "network sees (pixel / 255 - mean) / std (ImageNet networks: mean [0.485, 0.456, 0.406], std [0.229, 0.224, "
        "0.225])",
        file.string()));
  only_keys(j["normalisation"], {"mean", "std"}, "normalisation.", file);
  s.mean = per_channel(j["normalisation"], "mean", s.channels, false, file);
  s.std = per_channel(j["normalisation"], "std", s.channels, true, file);
  const std::string output = j.value("output", "");
  if (output != "probabilities" && output != "logits")
    throw InputError(
        fmt::format("'{}': 'output' is '{}'; give 'probabilities' (the network ends in a softmax) or 'logits' (riceasv "
                    "applies the softmax)",
                    file.string(), output));
  s.logits = output == "logits";
  return s;
}

OnnxClassifier OnnxClassifier::load(const std::filesystem::path& argument) {
  OnnxClassifier c;
  c.files_ = onnx_files(argument);
  const auto& f = c.files_;
  std::ifstream in(f.json);
  if (!in)
    throw InputError(
        fmt::format("the ONNX network '{}' needs '{}' beside it, giving the classes, the input size, crop_mm and the "
                    "normalisation ({}); write it",
                    f.onnx.string(), f.json.string(), kConvention));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("'{}' is not JSON ({}); write it as {} shows", f.json.string(), e.what(), kConvention));
  }
  c.spec_ = parse_onnx_spec(j, f.json);
  const OnnxSpec& s = c.spec_;

  // OpenCV logs an importer's failure on stderr besides throwing; the one line below says it all.
  const auto log_level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  try {
    const ImportableOnnx model = importable_onnx(f.onnx);
    c.net_ = cv::dnn::readNetFromONNX(model.bytes.data(), model.bytes.size());
    cv::utils::logging::setLogLevel(log_level);
  } catch (const cv::Exception& e) {
    cv::utils::logging::setLogLevel(log_level);
    const std::string reason = opencv_reason(e);
    if (reason.find("Failed to parse") != std::string::npos)
      throw InputError(fmt::format(
          "model file '{}' is not an ONNX network ({}); export the network to ONNX (torch.onnx.export, or tf2onnx "
          "for Keras; opset 11 to 13) and give that file",
          f.onnx.string(), reason));
    throw InputError(fmt::format(
        "model file '{}' is ONNX, but OpenCV {}'s dnn module cannot import it ({}); export it again with opset 11 to "
        "13 and common layers (Conv, BatchNormalization, Relu, pooling, Gemm, Softmax), or simplify it with "
        "onnx-simplifier",
        f.onnx.string(), CV_VERSION, reason.substr(0, 240)));
  }
  if (c.net_.empty())
    throw InputError(fmt::format(
        "model file '{}' holds no network OpenCV can run; export the network to ONNX (torch.onnx.export, or tf2onnx "
        "for Keras) and give that file",
        f.onnx.string()));
  c.net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  c.net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);

  // One blank grain through the network: the input size and the number of outputs are checked here,
  // before any photograph is measured.
  cv::Mat out;
  try {
    const int shape[] = {1, s.channels, s.height, s.width};
    c.net_.setInput(cv::Mat(4, shape, CV_32F, cv::Scalar(0)));
    out = c.net_.forward();
  } catch (const cv::Exception& e) {
    throw InputError(fmt::format(
        "the ONNX network '{}' does not run on a 1 x {} x {} x {} input (NCHW; OpenCV: {}); set input.channels, "
        "input.height and input.width in '{}' to the size it was exported with",
        f.onnx.string(), s.channels, s.height, s.width, opencv_reason(e), f.json.string()));
  }
  if (out.total() != s.classes.size())
    throw InputError(fmt::format(
        "the ONNX network '{}' gives {} score(s) per grain but '{}' names {} classes ({}); list one class per output "
        "in 'classes', in the network's output order, or export the network with a {}-way output",
        f.onnx.string(), out.total(), f.json.string(), s.classes.size(), fmt::join(s.classes, ", "), s.classes.size()));
  return c;
}

cv::Mat crop_for_network(const OnnxSpec& spec_, const cv::Mat& image, double x, double y, double mm_per_px, double fill,
                         cv::Rect* region) {
  const int n = std::max(1, static_cast<int>(std::lround(spec_.crop_mm / mm_per_px)));
  const cv::Rect square(static_cast<int>(std::lround(x - n / 2.0)), static_cast<int>(std::lround(y - n / 2.0)), n, n);
  if (region) *region = square;
  cv::Mat source = image;
  if (spec_.channels == 1 && image.channels() == 3) cv::cvtColor(image, source, cv::COLOR_BGR2GRAY);
  if (spec_.channels == 3 && image.channels() == 1) cv::cvtColor(image, source, cv::COLOR_GRAY2BGR);
  const int type = spec_.channels == 1 ? CV_8UC1 : CV_8UC3;
  cv::Mat cut(n, n, type, cv::Scalar::all(std::clamp(std::round(fill), 0.0, 255.0)));
  const cv::Rect inside = square & cv::Rect(0, 0, source.cols, source.rows);
  if (inside.area() > 0) source(inside).copyTo(cut(inside - square.tl()));
  cv::Mat resized;
  if (cut.cols == spec_.width && cut.rows == spec_.height)
    resized = cut;
  else
    cv::resize(cut, resized, cv::Size(spec_.width, spec_.height), 0, 0, cv::INTER_AREA);
  if (spec_.channels == 3 && spec_.rgb) cv::cvtColor(resized, resized, cv::COLOR_BGR2RGB);
  return resized;
}

std::vector<double> OnnxClassifier::scores(const cv::Mat& crop) const {
  const int shape[] = {1, spec_.channels, spec_.height, spec_.width};
  cv::Mat blob(4, shape, CV_32F);
  for (int c = 0; c < spec_.channels; ++c) {
    const double mean = spec_.mean[static_cast<std::size_t>(c)], sd = spec_.std[static_cast<std::size_t>(c)];
    for (int r = 0; r < spec_.height; ++r) {
      const unsigned char* row = crop.ptr<unsigned char>(r);
      float* to = blob.ptr<float>(0, c, r);
      for (int col = 0; col < spec_.width; ++col)
        to[col] = static_cast<float>((row[col * spec_.channels + c] / 255.0 - mean) / sd);
    }
  }
  net_.setInput(blob);
  const cv::Mat out = net_.forward();
  std::vector<double> s(out.total());
  const float* v = out.ptr<float>();
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = v[k];
  if (spec_.logits) {
    const double top = *std::max_element(s.begin(), s.end());
    double sum = 0;
    for (double& x : s) sum += (x = std::exp(x - top));
    for (double& x : s) x /= sum;
  }
  return s;
}

}  // namespace suite::rice
