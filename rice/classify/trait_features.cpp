#include "rice/classify/trait_features.hpp"

#include <cmath>
#include <stdexcept>

namespace suite::rice {

const std::vector<std::string>& feature_names() {
  static const std::vector<std::string> names = {"gel_kernel_ratio_log", "has_kernel",      "collar_completeness",
                                                 "kernel_pieces",        "kernel_solidity", "kernel_share",
                                                 "kernel_area_mm2",      "gel_area_mm2",    "grain_area_mm2",
                                                 "kernel_length_mm",     "kernel_width_mm"};
  return names;
}

cv::Mat features_of(const GrainTraits& t) {
  const bool has_kernel = t.kernel_pieces > 0 && t.kernel_area_mm2 > 0;
  const double ratio =
      has_kernel && std::isfinite(t.gel_kernel_ratio) ? std::min(t.gel_kernel_ratio, kRatioCap) : kRatioCap;
  const double values[] = {std::log1p(ratio),
                           has_kernel ? 1.0 : 0.0,
                           t.collar_completeness,
                           static_cast<double>(t.kernel_pieces),
                           has_kernel && std::isfinite(t.kernel_solidity) ? t.kernel_solidity : 0.0,
                           t.kernel_share,
                           t.kernel_area_mm2,
                           t.gel_area_mm2,
                           t.grain_area_mm2,
                           has_kernel ? t.kernel_length_mm : 0.0,
                           has_kernel ? t.kernel_width_mm : 0.0};
  cv::Mat row(1, static_cast<int>(std::size(values)), CV_32F);
  for (int i = 0; i < row.cols; ++i) {
    // The measurement defines every trait but the two handled above; anything else is a bug there.
    if (!std::isfinite(values[i]))
      throw std::logic_error("features_of: trait '" + feature_names()[static_cast<std::size_t>(i)] + "' is not finite");
    row.at<float>(0, i) = static_cast<float>(values[i]);
  }
  return row;
}

}  // namespace suite::rice
