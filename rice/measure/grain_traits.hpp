#pragma once
// Segmentation of every grain in a photograph of grains in alkali and its traits (docs/rice.md,
// "Measurement"):
//   grain   = connected component (8-neighbours) of the pixels above the grain threshold
//             (dish_levels.hpp), at least min_grain_mm2;
//   kernel  = its pixels above the kernel threshold; pieces are the kernel's connected components of
//             at least min_piece_mm2 (smaller specks are not counted anywhere);
//   gel     = its other pixels, after a morphological opening of gel_opening_mm that removes the
//             one- or two-pixel rim a kernel's blurred edge leaves between the two thresholds where
//             the kernel meets the dish directly.
// Traits, in mm and mm^2 from the pixel size:
//   kernel area, pieces, solidity (area / convex hull of all pieces: cracks and dispersion lower it),
//   length and width (the pieces' smallest enclosing rectangle); gel area and its ratio to the kernel;
//   collar completeness: the fraction of `angular_bins` directions from the kernel's centroid
//   (the grain's without a kernel) that hold gel; kernel share: the kernel's part of the grain's
//   brightness above the dish (1 for an intact kernel without gel, 0 with no kernel left).
// Quality flags (a flagged grain's numbers are written but its status is not ok):
//   cut_by_frame  the grain touches the image border, so part of it may be missing;
//   touching      two whole kernels in one grain (two pieces each longer than whole_kernel_mm), or
//                 kernel pieces spanning more than max_kernel_width_mm across (the pieces of one
//                 split kernel lie along its length): neighbours merged into one grain.
// Not collective.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rice/measure/dish_levels.hpp"

namespace suite::rice {

struct MeasureOptions {
  double mm_per_px = 0;              // pixel size, required
  double min_grain_mm2 = 1.0;        // smaller components are dust
  double min_piece_mm2 = 0.25;       // smaller kernel fragments are not pieces (a grade-5 piece is over 1 mm^2)
  double gel_opening_mm = 0.1;       // opening diameter for the gel (at least 3 pixels)
  int angular_bins = 360;            // directions for the collar completeness
  double whole_kernel_mm = 4.6;      // a piece this long is a whole kernel (milled rice: 5-7 mm)
  double max_kernel_width_mm = 3.4;  // a kernel wider than this is two kernels side by side (2-2.5 mm, swollen 2.8)
  LevelOptions levels;
};

struct GrainTraits {
  int grain = 0;              // 1, 2, ... in the order of the components' first pixels (top to bottom)
  double x_px = 0, y_px = 0;  // the kernel's centroid (the grain's without a kernel)
  bool ok = true;
  std::string quality;  // flags, ';'-separated
  double kernel_area_mm2 = 0;
  int kernel_pieces = 0;
  double kernel_solidity = 0;  // NaN without a kernel
  double kernel_length_mm = 0, kernel_width_mm = 0;
  double gel_area_mm2 = 0;
  double gel_kernel_ratio = 0;  // NaN without a kernel
  double collar_completeness = 0;
  double kernel_share = 0;
  double grain_area_mm2 = 0;
};

struct ImageTraits {
  DishLevels levels;
  std::vector<GrainTraits> grains;
  cv::Mat labels;  // CV_32S, the grain components (0 = dish), for overlays
  cv::Mat kernel;  // CV_8U, 255 = kernel pixel
  cv::Mat gel;     // CV_8U, 255 = gel pixel
};

// InputError for an invalid image or options (naming the option and its range).
ImageTraits measure_grains(const cv::Mat& grey, const MeasureOptions& options);

}  // namespace suite::rice
