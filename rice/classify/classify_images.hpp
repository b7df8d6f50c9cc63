#pragma once
// `riceasv classify IMAGES... --model MODEL_DIR` (docs/rice.md, "Classifying"): loads a model that
// `riceasv train` saved (before any image is read, so a wrong model stops at once), measures the
// images as `riceasv measure` does and predicts each grain's class. Writes into DIR:
//   classes.csv     one row per grain: image, grain, position, status (ok / flagged / failed, as in
//                   results.csv), quality, predicted class, its vote share (rtrees; empty for svm),
//                   message; a failed image has one row with its reason;
//   classify.json   the model, the counts per class over the ok grains, per image the counts and the
//                   most frequent class, the failed images, and the time per grain;
//   results.csv, measure.json   the traits, as `riceasv measure` writes them.
// classify_images_onnx() writes the same tables with a network's classes and scores.
// Flagged grains get a prediction too, but like their traits it is not to be trusted (their status
// says so) and they are left out of the counts. Not collective.
#include <filesystem>
#include <string>
#include <vector>

#include "core/log/logger.hpp"
#include "rice/measure/grain_traits.hpp"

namespace suite::rice {

struct ClassifySummary {
  int images = 0, failed_images = 0;
  int grains = 0, flagged = 0;
  std::string first_failure;  // the first failed image's message
};

// A network trained with `--model-type cnn` is run as an ONNX network is below (crops, scores.csv and,
// with `write_crops`, the crops); `write_crops` with a traits model is an InputError.
ClassifySummary classify_images(const std::vector<std::filesystem::path>& targets,
                                const std::filesystem::path& model_dir, const MeasureOptions& measure,
                                const std::filesystem::path& out, bool write_crops, Logger& log);

// The same with a user's ONNX network (onnx_classifier.hpp; `onnx` is NET.onnx with NET.json beside it,
// or a folder holding net.onnx and net.json): each measured grain is cropped around its centroid, run
// through the network, and given the class with the highest score; classes.csv's share is that score.
// Also writes DIR/scores.csv (every class's score and the crop's place per grain) and, with
// `write_crops`, DIR/crops/<image stem>_g<grain>.png (the network's input before normalisation). The
// network is loaded and tried on a blank input before any photograph is read.
ClassifySummary classify_images_onnx(const std::vector<std::filesystem::path>& targets,
                                     const std::filesystem::path& onnx, const MeasureOptions& measure,
                                     const std::filesystem::path& out, bool write_crops, Logger& log);

}  // namespace suite::rice
