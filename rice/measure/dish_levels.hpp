#pragma once
// The grey levels that split a photograph of grains in alkali into dish, gel and kernel
// (docs/rice.md, "Thresholds"). A photograph holds up to three populations: the black dish (most
// of the pixels), the translucent grey gel and the chalky white kernels.
//   1. The dish: the median grey level of the image (the dish covers more than half of it) and its
//      noise, 1.4826 x the median absolute deviation.
//   2. The grain pixels, roughly: above dish + max(6 noise, min_contrast).
//   3. Otsu's threshold on the histogram of those pixels where the image is flat (grey-level slope
//      below flat_slope of the dish-to-white range per pixel, after a 1-pixel Gaussian smoothing)
//      splits them in two classes. The flat pixels are the populations' plateaus; the blurred
//      transitions between them would otherwise form a class of their own (a grade-2 dish of
//      kernels alone would look like kernels and gel). The classes are two populations (gel and
//      kernel) when the upper class's median stands at least `contrast` times as far above the dish
//      as the lower one's (a chalky kernel sends back about twice the light of the gel, a dispersing
//      remnant still 1.7 times; lighting and grain-to-grain differences within one population give
//      at most about 1.3) and the class means are
//      apart by more than `separation` pooled class standard deviations (a textured gel cut in two
//      gives about 2.7) and the smaller class holds at least `min_class_share` of the pixels. Otherwise there is one:
//      kernel when its median is above the middle of the range from the dish to white (chalky kernels are, translucent
//      gel is not), else gel.
//   4. Thresholds half-way between the medians of adjacent populations: a blurred edge between two
//      flat levels crosses the half-way level where the edge was (a symmetric blur keeps it there),
//      so areas come out free of the blur's bias. Otsu's threshold itself is the midpoint of the
//      class means (its fixed point, Ridler and Calvard 1978); medians keep the blurred
//      transitions' pixels from pulling the levels.
// Not collective.
#include <opencv2/core.hpp>
#include <string>

namespace suite::rice {

struct LevelOptions {
  double min_contrast = 8;        // grey levels above the dish before a pixel counts as grain
  double contrast = 1.6;          // upper class's level above the dish over the lower class's
  double separation = 3;          // class means apart by this many pooled standard deviations
  double min_class_share = 0.03;  // the smaller Otsu class's share of the flat grain pixels
  double flat_slope = 0.02;       // a pixel is flat below this slope, in (white - dish) per pixel
};

struct DishLevels {
  double dish = 0, noise = 0;     // the dish's median grey level and its noise (grey levels)
  double gel = -1, kernel = -1;   // medians of the populations found; -1: absent
  double grain_threshold = 256;   // a pixel above it is grain (kernel or gel)
  double kernel_threshold = 256;  // a grain pixel above it is kernel; 256: no kernels in the image
  double contrast = 0;            // of Otsu's two classes: (upper median - dish) / (lower median - dish)
  double separation = 0;          // of Otsu's two classes, in pooled standard deviations
  std::string populations;        // "gel and kernel", "kernel", "gel" or "none"
};

// InputError unless `grey` is a non-empty CV_8UC1 image.
DishLevels dish_levels(const cv::Mat& grey, const LevelOptions& options = {});

}  // namespace suite::rice
