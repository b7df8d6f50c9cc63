#pragma once
// A convolutional network that classifies each grain's ASV class from a crop of the photograph around
// it (docs/rice.md, "The convolutional network"), trained and run with libtorch (Debian's
// libtorch-dev, CPU). The crop is the ONNX path's (onnx_classifier.hpp): a square of crop_mm around
// the grain's centroid, grey, resized to input_px x input_px with area averaging; the network sees
// (pixel / 255 - mean) / std with the mean and spread of its training crops' pixels.
//
// The network: three blocks of 3x3 convolution (width, 2 width, 4 width channels), batch
// normalisation, ReLU and 2x2 max pooling (the last block averages over the whole map instead), then
// one linear layer to a score per class (logits; softmax gives the probabilities). With width 8 it has
// 6,099 weights: the rendered grades differ in the size and brightness of kernel and gel, which a
// few filters see; a lab with thousands of photographs can widen it (--cnn-width).
// Training: Adam on the cross-entropy, mini-batches in a seeded order, each crop turned by a random
// one of the eight rotations by 90 degrees and mirror images (a grain's orientation carries no
// grade). Weights start from libtorch's seeded initialisation: no ImageNet weights can be downloaded
// here, which costs little for these small grey crops but would cost accuracy on real photographs of
// few grains; pretrained weights are fine-tuned by pretrained_net.hpp or run through `classify --onnx`.
// Bit for bit reproducible for a given seed and thread count (libtorch's sums depend on the threads).
// On disk: MODEL_DIR/model.pt (libtorch's archive of the weights) and MODEL_DIR/model.json (the format,
// the classes, the architecture, the crop and the normalisation). Not collective.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/fitted_model.hpp"
#include "rice/classify/onnx_classifier.hpp"

namespace suite::rice {

struct CnnOptions {
  int input_px = 48;    // side of the network's input, pixels
  double crop_mm = 14;  // side of the crop around each grain, mm (a swollen kernel and its collar)
  int width = 8;        // channels of the first convolution (then 2x and 4x)
  int max_epochs = 80;  // select() tries 1..max_epochs; fit() runs `epochs`
  int epochs = 80;      // passes over the training crops in fit()
  int batch = 16;       // crops per step
  double learning_rate = 3e-3;
  double weight_decay = 1e-4;
  bool augment = true;     // the eight turns and mirror images
  int threads = 1;         // libtorch's threads (these small tensors gain little from more: a batch
                           // runs one process per core); 0: every core
  std::uint64_t seed = 1;  // weights, batch order and turns
};

// The crop a network of these options sees (classes and normalisation left empty), as the ONNX path
// describes its input: grey, input_px square, crop_mm.
OnnxSpec cnn_crop_spec(const CnnOptions& options);

class CnnClassifier : public FittedModel {
 public:
  // Trains on `crops` (CV_8U, one row per grain: its input_px x input_px crop, row after row, as
  // crop_for_network(cnn_crop_spec(options), ...) makes it) and each row's class index in `classes`,
  // for options.epochs passes. `after_epoch`, when given, is called after each pass with the pass's
  // number (1, 2, ...) and the model as it stands. InputError with fewer than two classes.
  static CnnClassifier fit(const cv::Mat& crops, const std::vector<int>& labels, const AsvClasses& classes,
                           const CnnOptions& options,
                           const std::function<void(int, const CnnClassifier&)>& after_epoch = {});

  // Prediction::share: the network's probability of the class.
  std::vector<Prediction> predict(const cv::Mat& crops) const override;
  // Every class's probability, one row per crop (CV_64F).
  cv::Mat probabilities(const cv::Mat& crops) const;
  // The probabilities of one crop as crop_for_network() makes it (input_px square, CV_8UC1).
  std::vector<double> scores(const cv::Mat& crop) const;

  void save(const std::filesystem::path& dir, const nlohmann::json& training) const override;
  // A saved network; InputError naming the file and the fix when a file is missing or not what
  // `riceasv train --model-type cnn` writes.
  static CnnClassifier load(const std::filesystem::path& dir);
  // Whether DIR/model.json says it holds a network (so `classify --model` knows which to load).
  static bool is_cnn_model(const std::filesystem::path& dir);

  const AsvClasses& classes() const override { return classes_; }
  const CnnOptions& options() const { return options_; }
  // The crop, classes and normalisation, as the ONNX path's spec (output: logits).
  OnnxSpec spec() const;
  // Architecture, weights count, normalisation and training parameters, for model.json.
  nlohmann::json description() const;

  struct Network;  // the libtorch module (grain_cnn.cpp)

 private:
  AsvClasses classes_;
  CnnOptions options_;
  double mean_ = 0, std_ = 1;         // of the training crops' pixels / 255
  std::shared_ptr<Network> network_;  // shared by copies; fixed once fitted
};

// Step 2 for a network (Learner::select): fed the validation grains' probabilities after each pass,
// keeps the pass with the lowest cross-entropy on them (ties: the earlier) and its predictions.
class EpochSelection {
 public:
  explicit EpochSelection(std::vector<int> validation_labels) : labels_(std::move(validation_labels)) {}
  void after_pass(int pass, const cv::Mat& probabilities);
  int best_pass() const { return best_pass_; }
  const std::vector<Prediction>& predicted() const { return predicted_; }
  // {"by", "max_epochs", "epochs", "validation_loss", "validation_accuracy"} for evaluation.json;
  // without validation grains (`labels` empty) {"by": "none...", "epochs": max_epochs}.
  nlohmann::json record(int max_epochs) const;

 private:
  std::vector<int> labels_;
  double best_loss_ = 0;
  int best_pass_ = 0;
  std::vector<Prediction> predicted_;
  std::vector<double> loss_, accuracy_;
};

// Learner::select for a network: with validation grains, `train(options, report)` trains a network
// for options.max_epochs passes and calls report(pass, its probabilities on `validation`) after each;
// options.epochs becomes the pass EpochSelection keeps (max_epochs without validation grains).
// Returns EpochSelection's record; `validation_predicted` gets the kept pass's predictions.
using PassReport = std::function<void(int, const cv::Mat&)>;
nlohmann::json select_passes(CnnOptions& options, const cv::Mat& validation, const std::vector<int>& validation_labels,
                             std::vector<Prediction>& validation_predicted,
                             const std::function<void(const CnnOptions&, const PassReport&)>& train);

// Fits networks of one set of options; select() trains on the training crops for max_epochs passes
// and keeps the pass with the lowest cross-entropy on the validation crops (ties: the earlier), which
// later fits then run.
class CnnLearner : public Learner {
 public:
  CnnLearner(AsvClasses classes, CnnOptions options)
      : classes_(std::move(classes)), options_(options), crop_(cnn_crop_spec(options)) {}
  std::unique_ptr<FittedModel> fit(const cv::Mat& crops, const std::vector<int>& labels) const override;
  nlohmann::json select(const cv::Mat& train, const std::vector<int>& train_labels, const cv::Mat& validation,
                        const std::vector<int>& validation_labels,
                        std::vector<Prediction>& validation_predicted) override;
  const CnnOptions& options() const { return options_; }
  const OnnxSpec* crop_spec() const override { return &crop_; }

 private:
  AsvClasses classes_;
  CnnOptions options_;
  OnnxSpec crop_;
};

}  // namespace suite::rice
