#include "rice/cnn/pretrained_net.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <torch/script.h>

#include <fstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "rice/cnn/torch_training.hpp"

namespace suite::rice {

struct PretrainedClassifier::Module {
  torch::jit::Module module;
};

namespace {

constexpr const char* kFormat = "riceasv pretrained classifier";
constexpr int kVersion = 1;
constexpr const char* kConvention = "docs/rice.md, \"Fine-tuning a pretrained network\"";

std::string first_line(const c10::Error& e) {
  std::string s = e.what_without_backtrace();
  return s.substr(0, s.find('\n'));
}

nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("'{}' is missing; {}", file.string(), what));
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(fmt::format("'{}' is not JSON; {}", file.string(), what));
  return j;
}

torch::jit::Module load_module(const std::filesystem::path& file, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(fmt::format("'{}' is missing; {}", file.string(), what));
  try {
    return torch::jit::load(file.string());
  } catch (const c10::Error& e) {
    throw InputError(fmt::format("'{}' is not a TorchScript module ({}); {}", file.string(), first_line(e), what));
  }
}

torch::Tensor forward(torch::jit::Module& m, const torch::Tensor& x) {
  return m.forward({x}).toTensor();
}

}  // namespace

CnnOptions fine_tuning_options() {
  CnnOptions o;
  o.learning_rate = 3e-4;
  o.max_epochs = o.epochs = 30;
  return o;
}

PretrainedClassifier PretrainedClassifier::load_pretrained(const std::filesystem::path& argument,
                                                           const AsvClasses& classes) {
  std::error_code ec;
  const bool folder = std::filesystem::is_directory(argument, ec);
  const auto pt = folder ? argument / "net.pt" : argument;
  auto json = pt;
  json.replace_extension(".json");
  const std::string what = fmt::format(
      "--pretrained takes NET.pt (TorchScript: torch.jit.script(model).save) with NET.json beside it, or a folder "
      "holding net.pt and net.json ({})",
      kConvention);
  PretrainedClassifier c;
  c.classes_ = classes;
  c.spec_ = parse_onnx_spec(read_json_file(json, what), json);
  if (c.spec_.classes != classes.names)
    throw InputError(
        fmt::format("'{}' names the classes [{}]; training with --classes {} needs [{}] in that order: "
                    "give the network a head of {} outputs in that order, or the other --classes",
                    json.string(), fmt::join(c.spec_.classes, ", "), classes.scheme, fmt::join(classes.names, ", "),
                    classes.count()));
  if (!c.spec_.logits)
    throw InputError(
        fmt::format("'{}': output must be \"logits\" for fine-tuning (the training takes the softmax "
                    "itself); export the network without its final softmax",
                    json.string()));
  c.module_ = std::make_shared<Module>(Module{load_module(pt, what)});
  c.source_ = {{"network", pt.string()}, {"description", json.string()}};
  c.options_ = fine_tuning_options();
  // A blank crop through it: the input size and the head must fit.
  const cv::Mat blank(1, c.spec_.width * c.spec_.height * c.spec_.channels, CV_8U, cv::Scalar(0));
  cv::Mat p;
  try {
    p = c.probabilities(blank);
  } catch (const c10::Error& e) {
    throw InputError(
        fmt::format("the network '{}' does not run on a {} x {} x {} input as '{}' says ({}); fix the "
                    "input size in the JSON",
                    pt.string(), c.spec_.channels, c.spec_.height, c.spec_.width, json.string(), first_line(e)));
  }
  if (p.cols != classes.count())
    throw InputError(
        fmt::format("the network '{}' gives {} score(s) per grain, the classes are {}; give it a head of "
                    "{} outputs",
                    pt.string(), p.cols, classes.count(), classes.count()));
  return c;
}

PretrainedClassifier PretrainedClassifier::fine_tuned(
    const cv::Mat& crops, const std::vector<int>& labels, const CnnOptions& options,
    const std::function<void(int, const PretrainedClassifier&)>& after_epoch) const {
  cnn::use_threads(options.threads);
  torch::manual_seed(options.seed);  // dropout, where the network has it
  PretrainedClassifier c = *this;
  c.options_ = options;
  {
    torch::NoGradGuard no_grad;  // the copy's weights are leaves the optimiser may own
    c.module_ = std::make_shared<Module>(Module{module_->module.clone()});
  }
  torch::jit::Module& m = c.module_->module;
  std::vector<torch::Tensor> parameters;
  for (const auto& p : m.parameters()) {
    p.set_requires_grad(true);
    parameters.push_back(p);
  }
  const torch::Tensor x = cnn::to_tensor(crops, spec_.width, spec_.height, spec_.channels, spec_.mean, spec_.std);
  cnn::train_epochs([&m](const torch::Tensor& batch) { return forward(m, batch); }, parameters,
                    [&m](bool on) { m.train(on); }, x, labels, options,
                    [&](int epoch) {
                      if (after_epoch) after_epoch(epoch, c);
                    });
  return c;
}

cv::Mat PretrainedClassifier::probabilities(const cv::Mat& crops) const {
  if (crops.rows == 0) return cv::Mat(0, classes_.count(), CV_64F);
  cnn::use_threads(options_.threads);
  torch::NoGradGuard no_grad;
  torch::jit::Module& m = module_->module;
  m.eval();
  return cnn::probabilities_of(
      forward(m, cnn::to_tensor(crops, spec_.width, spec_.height, spec_.channels, spec_.mean, spec_.std)));
}

std::vector<Prediction> PretrainedClassifier::predict(const cv::Mat& crops) const {
  return most_probable(probabilities(crops));
}

std::vector<double> PretrainedClassifier::scores(const cv::Mat& crop) const {
  const cv::Mat p = probabilities(crop.clone().reshape(1, 1));
  return std::vector<double>(p.begin<double>(), p.end<double>());
}

void PretrainedClassifier::save(const std::filesystem::path& dir, const nlohmann::json& training) const {
  create_model_folder(dir);
  const auto pt = dir / "model.pt";
  try {
    module_->module.save(pt.string());
  } catch (const c10::Error& e) {
    throw InputError(fmt::format("cannot write '{}': {}; choose a folder you can write", pt.string(), first_line(e)));
  }
  nlohmann::json spec = {{"format", "riceasv onnx classifier"},
                         {"version", 1},
                         {"classes", spec_.classes},
                         {"input",
                          {{"width", spec_.width},
                           {"height", spec_.height},
                           {"channels", spec_.channels},
                           {"colour_order", spec_.rgb ? "rgb" : "bgr"}}},
                         {"crop_mm", spec_.crop_mm},
                         {"normalisation", {{"mean", spec_.mean}, {"std", spec_.std}}},
                         {"output", "logits"}};
  nlohmann::json j = {{"format", kFormat},
                      {"version", kVersion},
                      {"model_file", "model.pt"},
                      {"model", "pretrained"},
                      {"classes", classes_json(classes_)},
                      {"network", spec},
                      {"pretrained", source_},
                      {"parameters",
                       {{"epochs", options_.epochs},
                        {"batch", options_.batch},
                        {"learning_rate", options_.learning_rate},
                        {"weight_decay", options_.weight_decay},
                        {"augment", options_.augment ? "8 turns and mirror images" : "none"},
                        {"threads", options_.threads},
                        {"seed", options_.seed}}},
                      {"training", training}};
  io::write_file_atomic(dir / "model.json", j.dump(2) + "\n");
}

bool PretrainedClassifier::is_pretrained_model(const std::filesystem::path& dir) {
  return model_format(dir) == kFormat;
}

PretrainedClassifier PretrainedClassifier::load(const std::filesystem::path& dir) {
  const std::string again = fmt::format(
      "give the folder that 'riceasv train LABELS --model-type pretrained --out {}' wrote (model.json and model.pt)",
      dir.string());
  const auto file = dir / "model.json";
  const auto j = read_json_file(file, again);
  if (j.value("format", "") != kFormat || j.value("version", 0) != kVersion)
    throw InputError(fmt::format("'{}' is not a {} of version {}; {}", file.string(), kFormat, kVersion, again));
  PretrainedClassifier c;
  try {
    c.classes_ = AsvClasses::parse(j.at("classes").at("scheme").get<std::string>());
    c.spec_ = parse_onnx_spec(j.at("network"), file);
    c.source_ = j.at("pretrained");
    const auto& p = j.at("parameters");
    c.options_.epochs = p.at("epochs").get<int>();
    c.options_.threads = p.at("threads").get<int>();
    c.options_.seed = p.at("seed").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("'{}' lacks what a model needs ({}); {}", file.string(), e.what(), again));
  }
  c.module_ = std::make_shared<Module>(Module{load_module(dir / j.value("model_file", "model.pt"), again)});
  return c;
}

std::unique_ptr<FittedModel> PretrainedLearner::fit(const cv::Mat& crops, const std::vector<int>& labels) const {
  return std::make_unique<PretrainedClassifier>(base_.fine_tuned(crops, labels, options_));
}

nlohmann::json PretrainedLearner::select(const cv::Mat& train, const std::vector<int>& train_labels,
                                         const cv::Mat& validation, const std::vector<int>& validation_labels,
                                         std::vector<Prediction>& validation_predicted) {
  return select_passes(options_, validation, validation_labels, validation_predicted,
                       [&](const CnnOptions& o, const PassReport& report) {
                         base_.fine_tuned(train, train_labels, o, [&](int pass, const PretrainedClassifier& m) {
                           report(pass, m.probabilities(validation));
                         });
                       });
}

}  // namespace suite::rice
