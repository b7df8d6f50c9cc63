#pragma once
// A lab's pretrained network, fine-tuned on its labelled photographs inside the suite and run by
// `classify --model` (docs/rice.md, "Fine-tuning a pretrained network"): the dissertation's method,
// an ImageNet ResNet-18 fine-tuned on graded grains, with weights a lab downloads elsewhere. The
// network comes as TorchScript (`torch.jit.script(model).save("net.pt")`, its head already giving one
// score per class) with net.json beside it in the ONNX path's convention (onnx_classifier.hpp:
// classes, input size and channels, crop_mm, normalisation; output "logits"). `--pretrained DIR`
// means DIR/net.pt and DIR/net.json; `--pretrained NET.pt` reads NET.json beside it.
// Fine-tuning trains every weight with the suite's loop (torch_training.hpp: Adam, the eight turns
// and mirror images) from the pretrained values, the passes chosen on the validation grains like
// the suite's own network. On disk: MODEL_DIR/model.pt (the fine-tuned TorchScript module, loadable
// in PyTorch with torch.jit.load) and model.json. Not collective.
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/fitted_model.hpp"
#include "rice/classify/onnx_classifier.hpp"
#include "rice/cnn/grain_cnn.hpp"

namespace suite::rice {

// Fine-tuning's defaults: smaller steps and fewer passes than training from scratch.
CnnOptions fine_tuning_options();

class PretrainedClassifier : public FittedModel {
 public:
  // The network of --pretrained, checked: net.json parses (the ONNX convention, output logits), its
  // classes are `classes`' names in order, net.pt is TorchScript, and a blank input gives one score
  // per class. InputError naming the file and the fix otherwise.
  static PretrainedClassifier load_pretrained(const std::filesystem::path& argument, const AsvClasses& classes);

  // A copy of this network trained on `crops` (rows as crop_for_network(spec(), ...) makes them,
  // flattened) for options.epochs passes; `after_epoch` as CnnClassifier::fit's.
  PretrainedClassifier fine_tuned(const cv::Mat& crops, const std::vector<int>& labels, const CnnOptions& options,
                                  const std::function<void(int, const PretrainedClassifier&)>& after_epoch = {}) const;

  std::vector<Prediction> predict(const cv::Mat& crops) const override;
  cv::Mat probabilities(const cv::Mat& crops) const;
  std::vector<double> scores(const cv::Mat& crop) const;  // one crop as crop_for_network() makes it

  void save(const std::filesystem::path& dir, const nlohmann::json& training) const override;
  static PretrainedClassifier load(const std::filesystem::path& dir);
  static bool is_pretrained_model(const std::filesystem::path& dir);

  const AsvClasses& classes() const override { return classes_; }
  const OnnxSpec& spec() const { return spec_; }

  struct Module;  // the TorchScript module (pretrained_net.cpp)

 private:
  AsvClasses classes_;
  OnnxSpec spec_;
  CnnOptions options_;     // the fine-tuning's
  nlohmann::json source_;  // where the pretrained network came from
  std::shared_ptr<Module> module_;
};

// Fine-tunes copies of one pretrained network; select() as CnnLearner's.
class PretrainedLearner : public Learner {
 public:
  PretrainedLearner(PretrainedClassifier base, CnnOptions options) : base_(std::move(base)), options_(options) {}
  std::unique_ptr<FittedModel> fit(const cv::Mat& crops, const std::vector<int>& labels) const override;
  nlohmann::json select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                        const std::vector<int>& validation_labels,
                        std::vector<Prediction>& validation_predicted) override;
  const OnnxSpec* crop_spec() const override { return &base_.spec(); }

 private:
  PretrainedClassifier base_;
  CnnOptions options_;
};

}  // namespace suite::rice
