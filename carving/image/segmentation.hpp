#pragma once
// Seed segmentation of a colour photograph (docs/methods/carving.md, two-view method, first step):
// BGR -> HSV, a fixed HSV range or an automatic (Otsu) threshold on one channel, morphological
// opening (removes specks) and closing (fills pinholes), external contours, and the largest contour
// whose area lies in [min_area, max_area] px, filled, as the seed's mask. Also the image reading
// helper and an overlay PNG for a person to check the result.
//
// OpenCV conventions: H in 0..180 (degrees / 2), S and V in 0..255. Wheat on the K-State blue
// background: seed H about 15-30, background H about 115. On the K-State photographs the specular
// highlight is nearly white (S < 60), so the default fixed range cuts a notch where the highlight
// meets the outline; the automatic (Otsu on hue) mode keeps it.
#include <array>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "carving/image/image_io.hpp"
#include "carving/image/mask.hpp"

namespace suite::carving {

struct SegmentationOptions {
  enum class Channel { hue, saturation, value };

  std::array<int, 3> hsv_low{0, 60, 0};       // inclusive lower bounds of H, S, V
  std::array<int, 3> hsv_high{30, 255, 255};  // inclusive upper bounds; H low > H high wraps through 180 -> 0
  // Otsu's threshold on `otsu_channel` instead of the fixed range; the seed is the class above the
  // threshold when otsu_seed_is_high. The default, hue with the seed below, separates brown (H about
  // 15-25) from blue (H about 115) whatever the shading; value (brightness) splits a seed whose
  // shaded side is dim into two classes and loses that side (seen on rendered and real images).
  bool automatic = false;
  Channel otsu_channel = Channel::hue;
  bool otsu_seed_is_high = false;
  int open_kernel_px = 3;   // elliptical kernel size of the opening; 0 or 1 = no opening
  int close_kernel_px = 3;  // elliptical kernel size of the closing; 0 or 1 = no closing
  double min_area = 15000;  // accepted contour area, px (the dissertation's 15,000-50,000 px)
  double max_area = 50000;
};

struct Segmentation {
  bool found = false;
  std::string reason;              // why nothing was found (empty when found)
  Mask mask;                       // the chosen contour filled (all zero when not found)
  std::vector<cv::Point> contour;  // its boundary pixels, in order
  double area = 0;                 // cv::contourArea of the contour (what the range tests), px
  cv::Rect bounding_box;           // axis-aligned box of the contour, px
  double other_area = 0;           // the largest other contour's area (a piece or another object), px
  double threshold = -1;           // Otsu's threshold when automatic, else -1
};

// Segments a colour image (CV_8UC3 BGR; CV_8UC4 BGRA and CV_8UC1 grey are converted). InputError
// for an empty image or invalid options (each message names the option and its valid range).
Segmentation segment(const cv::Mat& bgr, const SegmentationOptions& options = {});

// read_image + segment; errors name the file.
Segmentation segment_file(const std::filesystem::path& path, const SegmentationOptions& options = {});

// A line to draw on an overlay, e.g. a slice position, in pixel coordinates.
struct OverlayLine {
  cv::Point2d from;
  cv::Point2d to;
};

// Writes `bgr` with the segmentation drawn over it as PNG: the contour in green, the bounding box
// in yellow, `lines` in red, and the reason in red text when nothing was found. InputError naming
// the path when it cannot be written.
void write_overlay(const std::filesystem::path& path, const cv::Mat& bgr, const Segmentation& segmentation,
                   const std::vector<OverlayLine>& lines = {});

// Intersection over union of two masks of the same size (1 when both are empty).
double intersection_over_union(const Mask& a, const Mask& b);

}  // namespace suite::carving
