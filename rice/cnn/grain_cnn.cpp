// libtorch is included only in rice/cnn/ (its headers take half a minute to compile per file).
#include "rice/cnn/grain_cnn.hpp"

#include <fmt/format.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "rice/cnn/torch_training.hpp"

namespace suite::rice {

namespace {

constexpr const char* kFormat = "riceasv cnn classifier";
constexpr int kVersion = 1;

torch::nn::Conv2d conv3x3(int in, int out) {
  return torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, 3).padding(1));
}

}  // namespace

struct CnnClassifier::Network : torch::nn::Module {
  torch::nn::Sequential features{nullptr};
  torch::nn::Linear head{nullptr};

  Network(int width, int classes) {
    features = register_module(
        "features",
        torch::nn::Sequential(conv3x3(1, width), torch::nn::BatchNorm2d(width), torch::nn::ReLU(),
                              torch::nn::MaxPool2d(2),  //
                              conv3x3(width, 2 * width), torch::nn::BatchNorm2d(2 * width), torch::nn::ReLU(),
                              torch::nn::MaxPool2d(2),  //
                              conv3x3(2 * width, 4 * width), torch::nn::BatchNorm2d(4 * width), torch::nn::ReLU(),
                              torch::nn::AdaptiveAvgPool2d(1), torch::nn::Flatten()));
    head = register_module("head", torch::nn::Linear(4 * width, classes));
  }
  torch::Tensor forward(const torch::Tensor& x) { return head(features->forward(x)); }
  long weights() {
    long n = 0;
    for (const auto& p : parameters()) n += p.numel();
    return n;
  }
};

OnnxSpec cnn_crop_spec(const CnnOptions& options) {
  OnnxSpec spec;
  spec.width = spec.height = options.input_px;
  spec.channels = 1;
  spec.crop_mm = options.crop_mm;
  spec.logits = true;
  return spec;
}

CnnClassifier CnnClassifier::fit(const cv::Mat& crops, const std::vector<int>& labels, const AsvClasses& classes,
                                 const CnnOptions& options,
                                 const std::function<void(int, const CnnClassifier&)>& after_epoch) {
  if (crops.rows != static_cast<int>(labels.size())) throw std::logic_error("CnnClassifier::fit: one crop per label");
  const std::set<int> present(labels.begin(), labels.end());
  if (present.size() < 2)
    throw InputError(
        fmt::format("cannot train a network on {} grain(s) of {} class: it needs grains of at least two classes",
                    labels.size(), present.size()));
  cnn::use_threads(options.threads);
  torch::manual_seed(options.seed);
  CnnClassifier c;
  c.classes_ = classes;
  c.options_ = options;
  cv::Scalar mean, sd;
  cv::meanStdDev(crops.reshape(1, 1), mean, sd);
  c.mean_ = mean[0] / 255.0;
  c.std_ = sd[0] > 1e-3 ? sd[0] / 255.0 : 1.0;
  c.network_ = std::make_shared<Network>(options.width, classes.count());
  Network& net = *c.network_;

  const torch::Tensor x = cnn::to_tensor(crops, options.input_px, options.input_px, 1, {c.mean_}, {c.std_});
  cnn::train_epochs([&net](const torch::Tensor& batch) { return net.forward(batch); }, net.parameters(),
                    [&net](bool on) { net.train(on); }, x, labels, options,
                    [&](int epoch) {
                      if (after_epoch) after_epoch(epoch, c);
                    });
  return c;
}

cv::Mat CnnClassifier::probabilities(const cv::Mat& crops) const {
  if (crops.rows == 0) return cv::Mat(0, classes_.count(), CV_64F);
  cnn::use_threads(options_.threads);
  torch::NoGradGuard no_grad;
  network_->eval();
  return cnn::probabilities_of(
      network_->forward(cnn::to_tensor(crops, options_.input_px, options_.input_px, 1, {mean_}, {std_})));
}

std::vector<Prediction> CnnClassifier::predict(const cv::Mat& crops) const {
  return most_probable(probabilities(crops));
}

std::vector<double> CnnClassifier::scores(const cv::Mat& crop) const {
  if (crop.type() != CV_8UC1 || crop.rows != options_.input_px || crop.cols != options_.input_px)
    throw std::logic_error("CnnClassifier::scores: the crop must be CV_8UC1 of input_px x input_px");
  const cv::Mat p = probabilities(crop.clone().reshape(1, 1));
  return std::vector<double>(p.begin<double>(), p.end<double>());
}

OnnxSpec CnnClassifier::spec() const {
  OnnxSpec s = cnn_crop_spec(options_);
  s.classes = classes_.names;
  s.mean = {mean_};
  s.std = {std_};
  return s;
}

nlohmann::json CnnClassifier::description() const {
  const int w = options_.width;
  return {{"model", "cnn"},
          {"architecture",
           {{"blocks", fmt::format("conv3x3({0})+bn+relu+maxpool2, conv3x3({1})+bn+relu+maxpool2, "
                                   "conv3x3({2})+bn+relu+global average, linear({2}->{3})",
                                   w, 2 * w, 4 * w, classes_.count())},
            {"width", w},
            {"weights", network_ ? network_->weights() : 0}}},
          {"input",
           {{"width", options_.input_px},
            {"height", options_.input_px},
            {"channels", 1},
            {"crop_mm", options_.crop_mm},
            {"normalisation", {{"mean", mean_}, {"std", std_}, {"applied", "(pixel / 255 - mean) / std"}}}}},
          {"parameters",
           {{"epochs", options_.epochs},
            {"batch", options_.batch},
            {"learning_rate", options_.learning_rate},
            {"weight_decay", options_.weight_decay},
            {"augment", options_.augment ? "8 turns and mirror images" : "none"},
            {"threads", options_.threads},
            {"seed", options_.seed}}}};
}

void CnnClassifier::save(const std::filesystem::path& dir, const nlohmann::json& training) const {
  create_model_folder(dir);
  const auto pt = dir / "model.pt";
  try {
    torch::serialize::OutputArchive archive;
    network_->save(archive);
    archive.save_to(pt.string());
  } catch (const c10::Error& e) {
    throw InputError(
        fmt::format("cannot write '{}': {}; choose a folder you can write", pt.string(), e.what_without_backtrace()));
  }
  nlohmann::json j = {
      {"format", kFormat}, {"version", kVersion}, {"model_file", "model.pt"}, {"classes", classes_json(classes_)}};
  j.update(description());
  j["training"] = training;
  io::write_file_atomic(dir / "model.json", j.dump(2) + "\n");
}

bool CnnClassifier::is_cnn_model(const std::filesystem::path& dir) {
  return model_format(dir) == kFormat;
}

CnnClassifier CnnClassifier::load(const std::filesystem::path& dir) {
  const auto json_file = dir / "model.json";
  const std::string again = fmt::format(
      "give the folder that 'riceasv train LABELS --model-type cnn --out {}' wrote (model.json and model.pt), or "
      "train it again",
      dir.string());
  std::ifstream in(json_file);
  if (!in) throw InputError(fmt::format("model file '{}' is missing; {}", json_file.string(), again));
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || j.value("format", "") != kFormat)
    throw InputError(fmt::format("model file '{}' is not a {}; {}", json_file.string(), kFormat, again));
  if (j.value("version", 0) != kVersion)
    throw InputError(fmt::format("model file '{}' is version {}, this riceasv reads version {}; train it again",
                                 json_file.string(), j.value("version", 0), kVersion));
  CnnClassifier c;
  try {
    c.classes_ = AsvClasses::parse(j.at("classes").at("scheme").get<std::string>());
    c.options_.width = j.at("architecture").at("width").get<int>();
    const auto& input = j.at("input");
    c.options_.input_px = input.at("width").get<int>();
    c.options_.crop_mm = input.at("crop_mm").get<double>();
    c.mean_ = input.at("normalisation").at("mean").get<double>();
    c.std_ = input.at("normalisation").at("std").get<double>();
    const auto& p = j.at("parameters");
    c.options_.epochs = p.at("epochs").get<int>();
    c.options_.batch = p.at("batch").get<int>();
    c.options_.learning_rate = p.at("learning_rate").get<double>();
    c.options_.weight_decay = p.at("weight_decay").get<double>();
    c.options_.augment = p.at("augment").get<std::string>() != "none";
    c.options_.threads = p.at("threads").get<int>();
    c.options_.seed = p.at("seed").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("model file '{}' lacks what a network needs ({}); {}", json_file.string(), e.what(), again));
  }
  if (c.options_.width < 1 || c.options_.width > 1024 || c.options_.input_px < 8 || c.options_.input_px > 4096 ||
      !(c.options_.crop_mm > 0) || !(c.std_ > 0))
    throw InputError(
        fmt::format("model file '{}': width, input size, crop_mm or std out of range; {}", json_file.string(), again));
  const auto pt = dir / j.value("model_file", "model.pt");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(pt, ec))
    throw InputError(fmt::format("model file '{}' is missing; copy the whole model folder, or {}", pt.string(), again));
  c.network_ = std::make_shared<Network>(c.options_.width, c.classes_.count());
  // libtorch's load replaces each tensor with the archive's whatever its shape: compare them after.
  std::vector<std::pair<std::string, std::vector<int64_t>>> shapes;
  for (const auto& t : c.network_->named_parameters()) shapes.emplace_back(t.key(), t.value().sizes().vec());
  for (const auto& t : c.network_->named_buffers()) shapes.emplace_back(t.key(), t.value().sizes().vec());
  std::string reason;
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(pt.string());
    c.network_->load(archive);
    std::size_t k = 0;
    for (const auto& t : c.network_->named_parameters())
      if (t.value().sizes().vec() != shapes[k++].second && reason.empty())
        reason = fmt::format("'{}' has another shape", t.key());
    for (const auto& t : c.network_->named_buffers())
      if (t.value().sizes().vec() != shapes[k++].second && reason.empty())
        reason = fmt::format("'{}' has another shape", t.key());
  } catch (const c10::Error& e) {
    reason = e.what_without_backtrace();
    reason = reason.substr(0, reason.find('\n'));
  }
  if (!reason.empty())
    throw InputError(fmt::format("model file '{}' is not the weights of the network model.json describes ({}); {}",
                                 pt.string(), reason, again));
  c.network_->eval();
  return c;
}

std::unique_ptr<FittedModel> CnnLearner::fit(const cv::Mat& crops, const std::vector<int>& labels) const {
  return std::make_unique<CnnClassifier>(CnnClassifier::fit(crops, labels, classes_, options_));
}

void EpochSelection::after_pass(int pass, const cv::Mat& p) {
  double loss = 0;
  int right = 0;
  std::vector<Prediction> predicted = most_probable(p);
  for (int i = 0; i < p.rows; ++i) {
    const int truth = labels_[static_cast<std::size_t>(i)];
    loss -= std::log(std::max(p.at<double>(i, truth), 1e-12));
    right += predicted[static_cast<std::size_t>(i)].label == truth;
  }
  loss /= p.rows;
  loss_.push_back(loss);
  accuracy_.push_back(static_cast<double>(right) / p.rows);
  if (best_pass_ == 0 || loss < best_loss_) best_loss_ = loss, best_pass_ = pass, predicted_ = std::move(predicted);
}

nlohmann::json EpochSelection::record(int max_epochs) const {
  if (labels_.empty())
    return {
        {"by", "none: no validation grains, max_epochs passes"}, {"max_epochs", max_epochs}, {"epochs", max_epochs}};
  return {{"by", "the pass with the lowest cross-entropy on the validation grains"},
          {"max_epochs", max_epochs},
          {"epochs", best_pass_},
          {"validation_loss", loss_},
          {"validation_accuracy", accuracy_}};
}

nlohmann::json select_passes(CnnOptions& options, const cv::Mat& validation, const std::vector<int>& validation_labels,
                             std::vector<Prediction>& validation_predicted,
                             const std::function<void(const CnnOptions&, const PassReport&)>& train) {
  EpochSelection selection(validation.rows > 0 ? validation_labels : std::vector<int>{});
  options.epochs = options.max_epochs;
  if (validation.rows > 0) {
    train(options, [&](int pass, const cv::Mat& probabilities) { selection.after_pass(pass, probabilities); });
    options.epochs = selection.best_pass();
  }
  validation_predicted = selection.predicted();
  return selection.record(options.max_epochs);
}

nlohmann::json CnnLearner::select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                                  const std::vector<int>& validation_labels,
                                  std::vector<Prediction>& validation_predicted) {
  return select_passes(options_, validation, validation_labels, validation_predicted,
                       [&](const CnnOptions& o, const PassReport& report) {
                         CnnClassifier::fit(train, train_labels, classes_, o, [&](int pass, const CnnClassifier& m) {
                           report(pass, m.probabilities(validation));
                         });
                       });
}

}  // namespace suite::rice
