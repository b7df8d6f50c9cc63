#pragma once
// A classifier of the ASV class from a grain's trait features (trait_features.hpp), on OpenCV's ml
// module (docs/rice.md, "The model"):
//   rtrees  a random forest (cv::ml::RTrees, default): `trees` trees on bootstrap samples, each split
//           choosing among sqrt(features) random features; the share of trees voting for the
//           predicted class comes with each prediction;
//   svm     a support vector machine with an RBF kernel (cv::ml::SVM), C and gamma chosen by
//           OpenCV's trainAuto (5-fold cross-validation on the training grains); no vote share.
// Features are standardised ((x - mean) / standard deviation of the training grains) before either
// model: the SVM's RBF distance needs it, the forest's splits do not care. The scaling is saved with
// the model. On disk a model is a folder: model.yml (OpenCV's own file) and model.json (what this
// file format is, the classes, the features, the scaling, the parameters and how it was trained).
// Not collective.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>
#include <string>
#include <vector>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/fitted_model.hpp"

namespace suite::rice {

// rtrees and svm are this file's; cnn (the suite's network) and pretrained (a lab's TorchScript
// network, fine-tuned) learn from crops (rice/cnn/).
enum class ModelKind { rtrees, svm, cnn, pretrained };
std::string to_string(ModelKind kind);
// "rtrees", "svm", "cnn" or "pretrained"; InputError naming --model-type otherwise.
ModelKind parse_model_kind(const std::string& text);

struct ModelOptions {
  ModelKind kind = ModelKind::rtrees;
  int trees = 100;           // rtrees: trees in the forest
  int max_depth = 8;         // rtrees: deepest split
  int min_sample_count = 2;  // rtrees: a node with fewer grains is a leaf
  std::uint64_t seed = 1;    // rtrees: bootstrap samples and feature draws
};

class TraitClassifier : public FittedModel {
 public:
  // Trains on `features` (CV_32F, one row per grain, feature_names() columns) and each row's class
  // index in `classes` (options.kind rtrees or svm). InputError when the rows hold fewer than two
  // classes.
  static TraitClassifier fit(const cv::Mat& features, const std::vector<int>& labels, const AsvClasses& classes,
                             const ModelOptions& options);

  // Prediction::share: rtrees the share of the trees that voted for the class; svm NaN.
  std::vector<Prediction> predict(const cv::Mat& features) const override;

  // Writes DIR/model.yml and DIR/model.json; `training` goes under the latter's "training" key.
  void save(const std::filesystem::path& dir, const nlohmann::json& training) const override;
  // A saved model; InputError naming the file and the fix when the folder, either file, the format,
  // the model's kind or its features are not what `riceasv train` writes.
  static TraitClassifier load(const std::filesystem::path& dir);

  const AsvClasses& classes() const override { return classes_; }
  const ModelOptions& options() const { return options_; }
  // The model's parameters, the scaling and (rtrees) each feature's importance, for model.json.
  nlohmann::json description() const;

 private:
  cv::Mat standardised(const cv::Mat& features) const;

  AsvClasses classes_;
  ModelOptions options_;
  std::vector<double> mean_, scale_;
  cv::Ptr<cv::ml::StatModel> model_;
};

// Fits trait classifiers of one kind (rtrees or svm); select() chooses the forest's depth from
// {4, 8, 16} by validation accuracy (ties go to the shallower forest); an SVM's C and gamma are chosen
// by OpenCV's trainAuto inside every fit, so select() fits nothing for it.
class TraitLearner : public Learner {
 public:
  TraitLearner(AsvClasses classes, ModelOptions options) : classes_(std::move(classes)), options_(options) {}
  std::unique_ptr<FittedModel> fit(const cv::Mat& features, const std::vector<int>& labels) const override;
  nlohmann::json select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                        const std::vector<int>& validation_labels,
                        std::vector<Prediction>& validation_predicted) override;
  const ModelOptions& options() const { return options_; }

 private:
  AsvClasses classes_;
  ModelOptions options_;
};

}  // namespace suite::rice
