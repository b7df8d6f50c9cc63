#include "rice/classify/trait_classifier.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "rice/classify/trait_features.hpp"

namespace suite::rice {
namespace {

constexpr const char* kFormat = "riceasv traits classifier";
constexpr int kVersion = 1;

// The top node OpenCV's ml module writes for each model kind.
const char* opencv_node(ModelKind kind) {
  return kind == ModelKind::rtrees ? "opencv_ml_rtrees" : "opencv_ml_svm";
}

std::string train_again(const std::filesystem::path& dir) {
  return fmt::format(
      "give the folder that 'riceasv train LABELS --out {}' wrote (model.json and model.yml), or "
      "train it again",
      dir.string());
}

nlohmann::json read_model_json(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(fmt::format("--model '{}': no such folder; {}", dir.string(), train_again(dir)));
  const auto file = dir / "model.json";
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("model file '{}' is missing; {}", file.string(), train_again(dir)));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("model file '{}' is not JSON ({}); {}", file.string(), e.what(), train_again(dir)));
  }
  if (!j.is_object() || j.value("format", "") != kFormat)
    throw InputError(fmt::format("model file '{}' is not a {} (its format is '{}'); {}", file.string(), kFormat,
                                 j.is_object() ? j.value("format", "none") : "none", train_again(dir)));
  if (j.value("version", 0) != kVersion)
    throw InputError(fmt::format("model file '{}' is version {}, this riceasv reads version {}; train it again",
                                 file.string(), j.value("version", 0), kVersion));
  return j;
}

}  // namespace

std::string to_string(ModelKind kind) {
  switch (kind) {
    case ModelKind::rtrees:
      return "rtrees";
    case ModelKind::svm:
      return "svm";
    case ModelKind::cnn:
      return "cnn";
    case ModelKind::pretrained:
      return "pretrained";
  }
  return "unknown";
}

ModelKind parse_model_kind(const std::string& text) {
  if (text == "rtrees") return ModelKind::rtrees;
  if (text == "svm") return ModelKind::svm;
  if (text == "cnn") return ModelKind::cnn;
  if (text == "pretrained") return ModelKind::pretrained;
  throw InputError(
      fmt::format("--model-type '{}': give 'rtrees' (a random forest), 'svm' (RBF support vectors), 'cnn' (a "
                  "convolutional network on a crop around each grain) or 'pretrained' (your TorchScript network, "
                  "fine-tuned; with --pretrained)",
                  text));
}

TraitClassifier TraitClassifier::fit(const cv::Mat& features, const std::vector<int>& labels, const AsvClasses& classes,
                                     const ModelOptions& options) {
  const int n_features = static_cast<int>(feature_names().size());
  if (features.type() != CV_32F || features.cols != n_features || features.rows != static_cast<int>(labels.size()))
    throw std::logic_error("TraitClassifier::fit: features must be CV_32F, one row per label, one column per feature");
  if (options.kind != ModelKind::rtrees && options.kind != ModelKind::svm)
    throw std::logic_error("TraitClassifier::fit: a network is not a trait classifier");
  const std::set<int> present(labels.begin(), labels.end());
  if (present.size() < 2)
    throw InputError(
        fmt::format("cannot train a classifier on {} grain(s) of {} class: it needs grains of at least "
                    "two classes",
                    labels.size(), present.size()));
  TraitClassifier c;
  c.classes_ = classes;
  c.options_ = options;
  for (int f = 0; f < n_features; ++f) {
    cv::Scalar mean, sd;
    cv::meanStdDev(features.col(f), mean, sd);
    c.mean_.push_back(mean[0]);
    c.scale_.push_back(sd[0] > 1e-9 ? sd[0] : 1.0);  // a constant feature is left as it is, shifted
  }
  cv::Mat responses(static_cast<int>(labels.size()), 1, CV_32S);
  for (int i = 0; i < responses.rows; ++i) responses.at<int>(i) = labels[static_cast<std::size_t>(i)];
  cv::Mat var_type(1, n_features + 1, CV_8U, cv::Scalar(cv::ml::VAR_ORDERED));
  var_type.at<std::uint8_t>(n_features) = cv::ml::VAR_CATEGORICAL;
  const auto data = cv::ml::TrainData::create(c.standardised(features), cv::ml::ROW_SAMPLE, responses, cv::noArray(),
                                              cv::noArray(), cv::noArray(), var_type);
  if (options.kind == ModelKind::rtrees) {
    auto forest = cv::ml::RTrees::create();
    forest->setMaxDepth(options.max_depth);
    forest->setMinSampleCount(options.min_sample_count);
    forest->setActiveVarCount(0);  // sqrt(features) per split
    forest->setCalculateVarImportance(true);
    forest->setTermCriteria({cv::TermCriteria::MAX_ITER, options.trees, 0});
    cv::theRNG().state = options.seed;  // the forest draws its bootstrap samples from OpenCV's RNG
    forest->train(data);
    c.model_ = forest;
  } else {
    auto svm = cv::ml::SVM::create();
    svm->setType(cv::ml::SVM::C_SVC);
    svm->setKernel(cv::ml::SVM::RBF);
    cv::theRNG().state = options.seed;  // trainAuto shuffles the grains into its folds with it
    svm->trainAuto(data, std::min<int>(5, responses.rows));
    c.model_ = svm;
  }
  return c;
}

cv::Mat TraitClassifier::standardised(const cv::Mat& features) const {
  cv::Mat z(features.size(), CV_32F);
  for (int i = 0; i < features.rows; ++i)
    for (int f = 0; f < features.cols; ++f)
      z.at<float>(i, f) = static_cast<float>((features.at<float>(i, f) - mean_[static_cast<std::size_t>(f)]) /
                                             scale_[static_cast<std::size_t>(f)]);
  return z;
}

std::vector<Prediction> TraitClassifier::predict(const cv::Mat& features) const {
  std::vector<Prediction> out(static_cast<std::size_t>(features.rows));
  if (features.rows == 0) return out;
  if (features.type() != CV_32F || features.cols != static_cast<int>(mean_.size()))
    throw std::logic_error("TraitClassifier::predict: features must be CV_32F with one column per feature");
  const cv::Mat z = standardised(features);
  if (options_.kind == ModelKind::svm) {
    cv::Mat labels;
    model_->predict(z, labels);
    for (int i = 0; i < z.rows; ++i)
      out[static_cast<std::size_t>(i)] = {static_cast<int>(std::lround(labels.at<float>(i))),
                                          std::numeric_limits<double>::quiet_NaN()};
    return out;
  }
  // Row 0 of the votes holds the class labels the forest knows, the next rows each grain's votes.
  cv::Mat votes;
  model_.dynamicCast<cv::ml::RTrees>()->getVotes(z, votes, 0);
  for (int i = 0; i < z.rows; ++i) {
    int best = 0, total = 0;
    for (int k = 0; k < votes.cols; ++k) {
      total += votes.at<int>(i + 1, k);
      if (votes.at<int>(i + 1, k) > votes.at<int>(i + 1, best)) best = k;
    }
    out[static_cast<std::size_t>(i)] = {votes.at<int>(0, best),
                                        total > 0 ? static_cast<double>(votes.at<int>(i + 1, best)) / total : 0.0};
  }
  return out;
}

nlohmann::json TraitClassifier::description() const {
  nlohmann::json parameters;
  if (options_.kind == ModelKind::rtrees) {
    parameters = {{"trees", options_.trees},
                  {"max_depth", options_.max_depth},
                  {"min_sample_count", options_.min_sample_count},
                  {"features_per_split", "sqrt(features)"},
                  {"seed", options_.seed}};
  } else {
    auto svm = model_.dynamicCast<cv::ml::SVM>();
    parameters = {{"kernel", "rbf"}, {"C", svm->getC()}, {"gamma", svm->getGamma()}, {"seed", options_.seed}};
  }
  nlohmann::json j = {{"model", to_string(options_.kind)},
                      {"parameters", parameters},
                      {"scaling", {{"mean", mean_}, {"scale", scale_}, {"applied", "(x - mean) / scale"}}}};
  if (options_.kind == ModelKind::rtrees) {
    const cv::Mat importance = model_.dynamicCast<cv::ml::RTrees>()->getVarImportance();
    nlohmann::json by_feature = nlohmann::json::object();
    for (int f = 0; f < static_cast<int>(importance.total()); ++f)
      by_feature[feature_names()[static_cast<std::size_t>(f)]] = importance.at<float>(f);
    j["feature_importance"] = by_feature;
  }
  return j;
}

void TraitClassifier::save(const std::filesystem::path& dir, const nlohmann::json& training) const {
  create_model_folder(dir);
  const auto yml = dir / "model.yml";
  try {
    model_->save(yml.string());
  } catch (const cv::Exception& e) {
    throw InputError(fmt::format("cannot write '{}': {}; choose a folder you can write", yml.string(), e.err));
  }
  nlohmann::json j = {{"format", kFormat},
                      {"version", kVersion},
                      {"model_file", "model.yml"},
                      {"classes", classes_json(classes_)},
                      {"features", feature_names()},
                      {"ratio_cap", kRatioCap},
                      {"feature_notes",
                       "gel_kernel_ratio_log = log(1 + min(ratio, ratio_cap)); no kernel: log(1 + ratio_cap), "
                       "has_kernel 0, kernel solidity, length and width 0"}};
  j.update(description());
  j["training"] = training;
  io::write_file_atomic(dir / "model.json", j.dump(2) + "\n");
}

TraitClassifier TraitClassifier::load(const std::filesystem::path& dir) {
  const nlohmann::json j = read_model_json(dir);
  const auto json_file = (dir / "model.json").string();
  TraitClassifier c;
  try {
    c.options_.kind = parse_model_kind(j.at("model").get<std::string>());
    c.classes_ = AsvClasses::parse(j.at("classes").at("scheme").get<std::string>());
    const auto features = j.at("features").get<std::vector<std::string>>();
    if (features != feature_names())
      throw InputError(
          fmt::format("model file '{}' was trained on the features [{}], this riceasv computes [{}]; "
                      "train the model again with this riceasv",
                      json_file, fmt::join(features, ", "), fmt::join(feature_names(), ", ")));
    c.mean_ = j.at("scaling").at("mean").get<std::vector<double>>();
    c.scale_ = j.at("scaling").at("scale").get<std::vector<double>>();
    const auto& p = j.at("parameters");
    c.options_.seed = p.at("seed").get<std::uint64_t>();
    if (c.options_.kind == ModelKind::rtrees) {
      c.options_.trees = p.at("trees").get<int>();
      c.options_.max_depth = p.at("max_depth").get<int>();
      c.options_.min_sample_count = p.at("min_sample_count").get<int>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("model file '{}' lacks what a model needs ({}); {}", json_file, e.what(), train_again(dir)));
  }
  if (c.mean_.size() != feature_names().size() || c.scale_.size() != feature_names().size())
    throw InputError(fmt::format("model file '{}' has a scaling of {} features, not {}; {}", json_file, c.mean_.size(),
                                 feature_names().size(), train_again(dir)));
  const auto yml = dir / j.value("model_file", "model.yml");
  const std::string wanted = to_string(c.options_.kind) == "rtrees" ? "an OpenCV RTrees model" : "an OpenCV SVM model";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(yml, ec))
    throw InputError(
        fmt::format("model file '{}' is missing; copy the whole model folder, or {}", yml.string(), train_again(dir)));
  std::string top;
  try {
    cv::FileStorage fs(yml.string(), cv::FileStorage::READ);
    if (fs.isOpened() && !fs.root().empty() && fs.root().isMap() && fs.root().size() > 0)
      top = (*fs.root().begin()).name();
    if (top == opencv_node(c.options_.kind)) {
      if (c.options_.kind == ModelKind::rtrees)
        c.model_ = cv::Algorithm::load<cv::ml::RTrees>(yml.string());
      else
        c.model_ = cv::Algorithm::load<cv::ml::SVM>(yml.string());
    }
  } catch (const cv::Exception& e) {
    throw InputError(fmt::format("model file '{}' is not {} OpenCV can read ({}); {}", yml.string(), wanted, e.err,
                                 train_again(dir)));
  }
  if (!c.model_ || !c.model_->isTrained() || c.model_->getVarCount() != static_cast<int>(feature_names().size()))
    throw InputError(fmt::format("model file '{}' is not {} of {} features (its top node is '{}', expected '{}'); {}",
                                 yml.string(), wanted, feature_names().size(), top.empty() ? "unreadable" : top,
                                 opencv_node(c.options_.kind), train_again(dir)));
  return c;
}

std::unique_ptr<FittedModel> TraitLearner::fit(const cv::Mat& features, const std::vector<int>& labels) const {
  return std::make_unique<TraitClassifier>(TraitClassifier::fit(features, labels, classes_, options_));
}

nlohmann::json TraitLearner::select(const cv::Mat& train, const std::vector<int>& train_labels,
                                    const cv::Mat& validation, const std::vector<int>& validation_labels,
                                    std::vector<Prediction>& validation_predicted) {
  nlohmann::json selection = {{"by", "validation accuracy"}};
  validation_predicted.clear();
  if (options_.kind != ModelKind::rtrees || validation.rows == 0) {
    selection["by"] = options_.kind == ModelKind::svm ? "OpenCV trainAuto (C, gamma; 5-fold on the training grains)"
                                                      : "none: no validation grains, the default depth";
    return selection;
  }
  double best = -1;
  int best_depth = options_.max_depth;
  for (int depth : {4, 8, 16}) {
    ModelOptions trial = options_;
    trial.max_depth = depth;
    const auto predicted = TraitClassifier::fit(train, train_labels, classes_, trial).predict(validation);
    int right = 0;
    for (std::size_t i = 0; i < predicted.size(); ++i) right += predicted[i].label == validation_labels[i];
    const double accuracy = static_cast<double>(right) / validation.rows;
    selection["tried"].push_back({{"max_depth", depth}, {"validation_accuracy", accuracy}});
    if (accuracy > best) best = accuracy, best_depth = depth, validation_predicted = predicted;
  }
  options_.max_depth = best_depth;
  selection["max_depth"] = best_depth;
  return selection;
}

}  // namespace suite::rice
