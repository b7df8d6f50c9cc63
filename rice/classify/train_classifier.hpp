#pragma once
// `riceasv train LABELS --out MODEL_DIR` (docs/rice.md, "Training"): measures the labelled photographs
// (labelled_images.hpp) with the measurement of `riceasv measure`, turns each ok grain into features,
// trains and judges a classifier (train_evaluate.hpp) and writes into MODEL_DIR:
//   model.yml, model.json       the model (trait_classifier.hpp);
//   evaluation.json             split, selection, validation / test / k-fold accuracies, per-class
//                               accuracies, confusion matrices, excluded grains, failed images, times;
//   confusion_test.csv, confusion_cv.csv, confusion.png   the test split's and the pooled k-fold matrix;
//   samples.csv                 one row per measured grain: its grade, class, status, set, fold and
//                               predictions;
//   measured/results.csv, measured/measure.json   the measurement, as `riceasv measure` writes it.
// Flagged grains (touching, cut by the frame) are not trained on; they are counted by reason. An image
// that cannot be measured, or a grade folder without images, does not stop the training: each is
// listed in `problems` (and evaluation.json), and the model is trained on the rest. Not collective.
#include <filesystem>
#include <string>
#include <vector>

#include "core/log/logger.hpp"
#include "rice/classify/train_evaluate.hpp"
#include "rice/measure/grain_traits.hpp"

namespace suite::rice {

struct TrainSummary {
  int images = 0;                     // labelled images
  int grains_used = 0;                // ok grains trained and judged on
  int grains_excluded = 0;            // flagged grains
  double test_accuracy = 0;           // NaN without test grains
  double cv_accuracy = 0;             // pooled over the folds; NaN without folds
  std::vector<std::string> problems;  // failed images and empty grade folders, one line each
};

TrainSummary train_classifier(const std::filesystem::path& labels, const TrainOptions& options,
                              const MeasureOptions& measure, const std::filesystem::path& out, Logger& log);

}  // namespace suite::rice
