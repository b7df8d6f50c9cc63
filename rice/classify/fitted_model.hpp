#pragma once
// What `riceasv train` needs of any kind of model (docs/rice.md, "Training"): a model fitted on some
// grains predicts others and saves itself, and a learner fits such models and chooses its own
// parameters on the validation grains. Grains are the rows of a sample matrix with one row per grain,
// whose meaning the kind fixes: the trait classifier's rows are its features (CV_32F), the
// convolutional network's its crop around the grain (CV_8U, the crop's pixels row after row). The
// same seeded split, final fit and k-fold cross-validation (train_evaluate.hpp) judge every kind.
// Not collective.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rice/classify/asv_classes.hpp"

namespace suite::rice {

struct OnnxSpec;  // onnx_classifier.hpp

struct Prediction {
  int label = -1;     // class index
  double share = -1;  // the model's confidence in it, in (0, 1]: the forest's vote share, the network's
                      // probability; NaN where the model has none (svm)
};

class FittedModel {
 public:
  virtual ~FittedModel() = default;
  // One prediction per row of `samples` (rows as the learner that fitted the model takes them).
  virtual std::vector<Prediction> predict(const cv::Mat& samples) const = 0;
  // Writes the model into `dir` (model.json and the kind's own files); `training` goes under
  // model.json's "training" key.
  virtual void save(const std::filesystem::path& dir, const nlohmann::json& training) const = 0;
  virtual const AsvClasses& classes() const = 0;
};

// What every saved model shares: the folder, created (InputError naming it when it cannot be), and
// model.json's "classes" entry: {"scheme", "names", "grades"}.
void create_model_folder(const std::filesystem::path& dir);
nlohmann::json classes_json(const AsvClasses& classes);
// DIR/model.json's "format" ("riceasv cnn classifier", ...), or "" when the file is missing or not
// a JSON object.
std::string model_format(const std::filesystem::path& dir);

// Each row's most probable class and its probability, from a CV_64F table of one row per grain and
// one column per class (a network's softmax).
std::vector<Prediction> most_probable(const cv::Mat& probabilities);

class Learner {
 public:
  virtual ~Learner() = default;
  // Fits a model on `samples` (one row per grain) and each row's class.
  virtual std::unique_ptr<FittedModel> fit(const cv::Mat& samples, const std::vector<int>& labels) const = 0;
  // Chooses the learner's parameters by fitting on `train` and judging on `validation` (rows and their
  // labels), and keeps them for later fits. Returns what it tried and chose, for evaluation.json, and
  // the chosen model's predictions of the validation rows in `validation_predicted` (left empty when
  // the choice judged none, e.g. without validation grains).
  virtual nlohmann::json select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                                const std::vector<int>& validation_labels,
                                std::vector<Prediction>& validation_predicted) = 0;
  // The crop its rows are (onnx_classifier.hpp's rule), for a learner of crops; nullptr for one of
  // trait features.
  virtual const OnnxSpec* crop_spec() const { return nullptr; }
};

}  // namespace suite::rice
