// The only file of the suite that includes libtorch (its headers take half a minute to compile).
#include "rice/cnn/grain_cnn.hpp"

#include <fmt/format.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <thread>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

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

namespace {

// libtorch's thread count for this process: the option, else the cores it may run on.
void use_threads(int threads) {
  const int n = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (torch::get_num_threads() != n) torch::set_num_threads(n);
}

// Rows of CV_8U crops as an N x 1 x side x side float tensor of (pixel / 255 - mean) / std.
torch::Tensor to_tensor(const cv::Mat& crops, int side, double mean, double std) {
  if (crops.rows > 0 && (crops.type() != CV_8UC1 || crops.cols != side * side || !crops.isContinuous()))
    throw std::logic_error(
        fmt::format("CnnClassifier: crops must be continuous CV_8UC1 rows of {} x {} pixels", side, side));
  cv::Mat scaled;
  crops.convertTo(scaled, CV_32F, 1.0 / (255.0 * std), -mean / std);
  return torch::from_blob(scaled.data, {crops.rows, 1, side, side}, torch::kFloat32).clone();
}

// One of the eight turns and mirror images of each crop in `batch` (N x 1 x H x W), drawn from `rng`.
torch::Tensor turned(const torch::Tensor& batch, std::mt19937_64& rng) {
  std::vector<torch::Tensor> out;
  out.reserve(static_cast<std::size_t>(batch.size(0)));
  for (int64_t i = 0; i < batch.size(0); ++i) {
    const auto k = static_cast<int64_t>(rng() % 8);
    torch::Tensor x = torch::rot90(batch[i], k % 4, {1, 2});
    if (k >= 4) x = torch::flip(x, {2});
    out.push_back(x);
  }
  return torch::stack(out);
}

}  // namespace

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
  use_threads(options.threads);
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

  const torch::Tensor x = to_tensor(crops, options.input_px, c.mean_, c.std_);
  const torch::Tensor y = torch::tensor(std::vector<int64_t>(labels.begin(), labels.end()), torch::kInt64);
  torch::optim::Adam optimiser(net.parameters(),
                               torch::optim::AdamOptions(options.learning_rate).weight_decay(options.weight_decay));
  std::mt19937_64 rng(options.seed);
  std::vector<int64_t> order(static_cast<std::size_t>(crops.rows));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int64_t>(i);
  for (int epoch = 1; epoch <= options.epochs; ++epoch) {
    net.train();
    for (std::size_t i = order.size(); i > 1; --i)  // Fisher-Yates, the same with every standard library
      std::swap(order[i - 1], order[static_cast<std::size_t>(rng() % i)]);
    for (std::size_t start = 0; start < order.size(); start += static_cast<std::size_t>(options.batch)) {
      const std::size_t end = std::min(order.size(), start + static_cast<std::size_t>(options.batch));
      if (end - start < 2 && start > 0) break;  // batch normalisation needs two crops; one left over sits out
      const torch::Tensor index = torch::tensor(std::vector<int64_t>(order.begin() + static_cast<std::ptrdiff_t>(start),
                                                                     order.begin() + static_cast<std::ptrdiff_t>(end)),
                                                torch::kInt64);
      torch::Tensor batch = x.index_select(0, index);
      if (options.augment) batch = turned(batch, rng);
      optimiser.zero_grad();
      const torch::Tensor loss = torch::nn::functional::cross_entropy(net.forward(batch), y.index_select(0, index));
      loss.backward();
      optimiser.step();
    }
    if (after_epoch) after_epoch(epoch, c);
  }
  net.eval();
  return c;
}

cv::Mat CnnClassifier::probabilities(const cv::Mat& crops) const {
  cv::Mat out(crops.rows, classes_.count(), CV_64F);
  if (crops.rows == 0) return out;
  use_threads(options_.threads);
  torch::NoGradGuard no_grad;
  network_->eval();
  const torch::Tensor logits = network_->forward(to_tensor(crops, options_.input_px, mean_, std_));
  const torch::Tensor p = torch::softmax(logits.to(torch::kFloat64), 1);
  const auto a = p.accessor<double, 2>();
  for (int i = 0; i < crops.rows; ++i)
    for (int k = 0; k < classes_.count(); ++k) out.at<double>(i, k) = a[i][k];
  return out;
}

std::vector<Prediction> CnnClassifier::predict(const cv::Mat& crops) const {
  const cv::Mat p = probabilities(crops);
  std::vector<Prediction> out(static_cast<std::size_t>(crops.rows));
  for (int i = 0; i < p.rows; ++i) {
    cv::Point best;
    double top = 0;
    cv::minMaxLoc(p.row(i), nullptr, &top, nullptr, &best);
    out[static_cast<std::size_t>(i)] = {best.x, top};
  }
  return out;
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
  std::ifstream in(dir / "model.json");
  if (!in) return false;
  const auto j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && j.value("format", "") == kFormat;
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

nlohmann::json CnnLearner::select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                                  const std::vector<int>& validation_labels,
                                  std::vector<Prediction>& validation_predicted) {
  validation_predicted.clear();
  nlohmann::json selection = {{"by", "the pass with the lowest cross-entropy on the validation grains"},
                              {"max_epochs", options_.max_epochs}};
  if (validation.rows == 0) {
    options_.epochs = options_.max_epochs;
    selection["by"] = "none: no validation grains, max_epochs passes";
    selection["epochs"] = options_.epochs;
    return selection;
  }
  CnnOptions trial = options_;
  trial.epochs = options_.max_epochs;
  double best_loss = std::numeric_limits<double>::infinity();
  int best_epoch = trial.epochs;
  nlohmann::json loss_curve = nlohmann::json::array(), accuracy_curve = nlohmann::json::array();
  CnnClassifier::fit(train, train_labels, classes_, trial, [&](int epoch, const CnnClassifier& model) {
    const cv::Mat p = model.probabilities(validation);
    double loss = 0;
    int right = 0;
    std::vector<Prediction> predicted(static_cast<std::size_t>(p.rows));
    for (int i = 0; i < p.rows; ++i) {
      const int truth = validation_labels[static_cast<std::size_t>(i)];
      loss -= std::log(std::max(p.at<double>(i, truth), 1e-12));
      cv::Point best;
      double top = 0;
      cv::minMaxLoc(p.row(i), nullptr, &top, nullptr, &best);
      predicted[static_cast<std::size_t>(i)] = {best.x, top};
      right += best.x == truth;
    }
    loss /= p.rows;
    loss_curve.push_back(loss);
    accuracy_curve.push_back(static_cast<double>(right) / p.rows);
    if (loss < best_loss) best_loss = loss, best_epoch = epoch, validation_predicted = predicted;
  });
  options_.epochs = best_epoch;
  selection["epochs"] = best_epoch;
  selection["validation_loss"] = loss_curve;
  selection["validation_accuracy"] = accuracy_curve;
  return selection;
}

}  // namespace suite::rice
