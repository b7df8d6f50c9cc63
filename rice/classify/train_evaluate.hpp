#pragma once
// Training and judging a classifier on grains already turned into samples (docs/rice.md,
// "Training"), the part of `riceasv train` that needs no images. Every kind of model
// (fitted_model.hpp) is judged the same way:
//   1. a seeded stratified split into train, validation and test grains (75 / 12.5 / 12.5% by
//      default, as the dissertation's);
//   2. the learner's parameters chosen on the validation grains (Learner::select): the forest's
//      depth, the network's number of epochs; an SVM's C and gamma come from OpenCV's trainAuto on
//      the training grains;
//   3. the model fitted on train + validation grains and judged on the test grains, which no step
//      above has seen;
//   4. k-fold cross-validation over all grains with the same parameters: one accuracy per fold and
//      the pooled confusion matrix (every grain predicted once, by the model that did not see it).
// Not collective.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/evaluation.hpp"
#include "rice/classify/fitted_model.hpp"
#include "rice/classify/trait_classifier.hpp"
#include "rice/cnn/grain_cnn.hpp"

namespace suite::rice {

struct TrainOptions {
  AsvClasses classes = AsvClasses::three();
  ModelOptions model;                // the kind; rtrees and svm: their parameters
  CnnOptions cnn;                    // model.kind cnn or pretrained: the network's training
  std::filesystem::path pretrained;  // model.kind pretrained: NET.pt (with NET.json) or a folder of both
  double validation_share = 0.125;
  double test_share = 0.125;
  int folds = 5;           // 0: no cross-validation
  std::uint64_t seed = 1;  // the split, the folds and the model's own draws
};

struct Evaluation {
  std::unique_ptr<FittedModel> model;  // the final model (train + validation grains)
  Split split;
  nlohmann::json selection;  // what step 2 tried and chose
  Confusion validation, test, cross_validation;
  std::vector<double> fold_accuracy;
  std::vector<int> test_predicted;       // per grain: the final model's class for test grains, else -1
  std::vector<Prediction> cv_predicted;  // per grain: its fold's prediction (label -1 without folds)
  std::vector<int> fold;                 // per grain: its fold, -1 without folds
  double fit_seconds = 0;                // fitting the final model
  double predict_seconds_per_grain = 0;  // the final model over all grains, per grain
};

// `samples`: one row per grain, as `learner` takes them; `labels`: class indices. InputError when a
// class of `options.classes` has no grain, or for options out of range. `options.model` is not used:
// the learner holds its own options.
Evaluation train_and_evaluate(const cv::Mat& samples, const std::vector<int>& labels, const TrainOptions& options,
                              Learner& learner);

// The learner `options` ask for, seeded with options.seed: a TraitLearner of options.model (its rows
// are trait features), or for model.kind cnn a CnnLearner of options.cnn, for pretrained a
// PretrainedLearner of options.pretrained fine-tuned with options.cnn (their rows are crops, by the
// learner's crop_spec()). InputError for a pretrained network that cannot be used.
std::unique_ptr<Learner> make_learner(const TrainOptions& options);

// The trait classifier of `options.model` (rtrees or svm) on `features` (CV_32F, one row per grain).
Evaluation train_and_evaluate(const cv::Mat& features, const std::vector<int>& labels, const TrainOptions& options);

// The rows of `features` listed in `rows`, and their labels.
cv::Mat select_rows(const cv::Mat& features, const std::vector<int>& rows);

}  // namespace suite::rice
