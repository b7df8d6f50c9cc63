#pragma once
// The feature vector a classifier sees for one grain, from its measured traits (grain_traits.hpp;
// docs/rice.md, "Features"). Every entry is a finite number:
//   gel_kernel_ratio_log  log(1 + min(gel/kernel, kRatioCap)). Without a kernel (grade 7, some
//                         grade 6) the ratio is undefined (NaN in results.csv): it is the limit of a
//                         vanishing kernel, so it takes the cap, log(1 + 100), above any grain with
//                         a kernel left. The log keeps grades 2-5 (ratios 0-3) from being squeezed
//                         against the dispersed grades' ratios of 10 and more.
//   has_kernel            1 when a kernel piece was found, else 0: says the missing kernel outright,
//                         so a model need not infer it from the cap.
//   collar_completeness, kernel_pieces, kernel_share, kernel_area_mm2, gel_area_mm2, grain_area_mm2,
//   kernel_length_mm, kernel_width_mm   as measured (0 without a kernel);
//   kernel_solidity       as measured; 0 without a kernel (nothing solid left).
// Not collective.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rice/measure/grain_traits.hpp"

namespace suite::rice {

constexpr double kRatioCap = 100;  // gel/kernel ratios above it (and no kernel) count as this

// The features' names, in the order of features_of(); a saved model records them.
const std::vector<std::string>& feature_names();

// One row (CV_32F, 1 x feature_names().size()) for a grain.
cv::Mat features_of(const GrainTraits& traits);

}  // namespace suite::rice
