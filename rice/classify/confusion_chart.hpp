#pragma once
// A PNG of confusion matrices side by side, drawn with OpenCV (docs/rice.md, "Training"): one panel
// per matrix, true classes down, predicted across, each cell shaded by its share of the true class's
// grains and labelled with its count and that share; the title gives the accuracy and the grains.
// Not collective.
#include <filesystem>
#include <string>
#include <vector>

#include "rice/classify/evaluation.hpp"

namespace suite::rice {

struct ConfusionPanel {
  std::string title;  // e.g. "test split"
  Confusion confusion;
};

// InputError naming the path when it cannot be written.
void draw_confusion_chart(const std::filesystem::path& png, const std::vector<ConfusionPanel>& panels);

}  // namespace suite::rice
