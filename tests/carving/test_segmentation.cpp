// Tests of seed segmentation: rendered photographs of a wheat-sized ellipsoid (blurred, noisy)
// segment to their exact silhouettes; noise alone or a too-small seed is reported, not accepted;
// unreadable files and bad options are InputErrors that name the file or option.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "carving/image/segmentation.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::carving {
namespace {

using testing::scratch_dir;

// A parallel view of `scale` px/mm looking along +z: world x -> u, world y -> v.
View parallel_view(double scale, int width = 640, int height = 480) {
  View v;
  v.P << scale, 0, 0, width / 2.0, 0, scale, 0, height / 2.0, 0, 0, 0, 1;
  v.width = width;
  v.height = height;
  return v;
}

// The wheat ellipsoid 7.2 x 3.6 x 2.9 mm, turned 20 degrees in the image plane, at 40 px/mm: its
// silhouette is an ellipse of about 144 x 72 px semi-axes, 32,600 px, inside the default area
// range [15000, 50000].
Ellipsoid wheat() {
  Pose pose;
  pose.rotation = rotation_matrix({0, 0, 1}, 20 * std::numbers::pi / 180);
  pose.centre = {0.0137, -0.0219, 0};
  return Ellipsoid(3.6, 1.8, 1.45, pose);
}

RenderOptions photographic() {
  RenderOptions o;
  o.supersampling = 4;
  o.blur_sigma_px = 1.0;
  o.noise_sigma = 4;
  o.noise_seed = 7;
  return o;
}

// IoU threshold: the segmented boundary can be off by a fraction of a pixel along the contour
// (anti-aliased edge pixels are seed-coloured above roughly 40% coverage, then blur and noise move
// the edge a little). A full one-pixel ring on this ellipse (perimeter about 700 px, area 32,600 px)
// would cost 700 / 32,600 = 2.1% of IoU, so IoU > 0.98 allows about a whole pixel ring of error
// and still fails a mask that is dilated, eroded or shifted by a pixel. Measured: see the output.
constexpr double kMinIoU = 0.98;

TEST(Segmentation, RenderedEllipsoidSegmentsToItsExactMask) {
  const RenderedView view = render(wheat(), parallel_view(40), photographic());
  const Segmentation s = segment(view.image);
  ASSERT_TRUE(s.found) << s.reason;
  const double iou = intersection_over_union(s.mask, view.mask);
  std::printf("[ info ] HSV range: IoU %.5f, contour area %.0f px, mask %lld px, exact %lld px\n", iou, s.area,
              s.mask.area(), view.mask.area());
  EXPECT_GT(iou, kMinIoU);
  EXPECT_TRUE(s.reason.empty());
  EXPECT_EQ(s.threshold, -1);
  EXPECT_FALSE(s.contour.empty());
  EXPECT_GE(s.area, 15000);
  EXPECT_LE(s.area, 50000);
  // The box holds the contour.
  for (const cv::Point& p : s.contour) EXPECT_TRUE(s.bounding_box.contains(p));

  // A pixel-shifted mask must fail the threshold (it is a meaningful bound).
  std::vector<std::uint8_t> shifted(view.mask.pixels().size(), 0);
  for (int y = 0; y < view.mask.height(); ++y)
    for (int x = 2; x < view.mask.width(); ++x)
      shifted[static_cast<std::size_t>(y) * view.mask.width() + x] = view.mask.at(x - 2, y);
  EXPECT_LT(intersection_over_union(Mask(view.mask.width(), view.mask.height(), shifted), view.mask), kMinIoU);
}

// A red seed's hues straddle 0: OpenCV's H runs 0..180, and red shaded by the renderer's lighting
// and noise comes out near 0 and near 180 both. A range whose low hue exceeds its high hue wraps
// through red (docs/carving.md, "Profiles"); either half alone loses much of the seed.
TEST(Segmentation, HueRangeWrapsThroughRed) {
  RenderOptions o = photographic();
  o.seed_bgr = {45, 45, 230};  // pure red (hue 0): the noise puts its pixels either side of 0
  const RenderedView view = render(wheat(), parallel_view(40), o);
  SegmentationOptions red;
  red.hsv_low = {170, 80, 40};
  red.hsv_high = {10, 255, 255};
  const Segmentation s = segment(view.image, red);
  ASSERT_TRUE(s.found) << s.reason;
  const double iou = intersection_over_union(s.mask, view.mask);
  std::printf("[ info ] hue range through red: IoU %.5f\n", iou);
  EXPECT_GT(iou, kMinIoU);
  for (const auto& half : {std::array<int, 2>{170, 180}, std::array<int, 2>{0, 10}}) {
    SegmentationOptions part = red;
    part.hsv_low[0] = half[0], part.hsv_high[0] = half[1];
    const Segmentation p = segment(view.image, part);
    EXPECT_LT(p.found ? intersection_over_union(p.mask, view.mask) : 0.0, kMinIoU) << half[0] << ".." << half[1];
  }
}

TEST(Segmentation, AutomaticOtsuThresholdFindsTheSeed) {
  const RenderedView view = render(wheat(), parallel_view(40), photographic());
  SegmentationOptions o;
  o.automatic = true;  // Otsu on hue: the seed (H about 15-25) below the blue background (H about 115)
  const Segmentation s = segment(view.image, o);
  ASSERT_TRUE(s.found) << s.reason;
  const double iou = intersection_over_union(s.mask, view.mask);
  std::printf("[ info ] Otsu on H: threshold %.0f, IoU %.5f\n", s.threshold, iou);
  EXPECT_GT(iou, kMinIoU);
  EXPECT_GT(s.threshold, 30);
  EXPECT_LT(s.threshold, 115);

  // Otsu on V (brightness) suits an evenly lit seed; a strongly shaded one it splits (see the header).
  RenderOptions even = photographic();
  even.ambient = 0.8;
  const RenderedView lit = render(wheat(), parallel_view(40), even);
  o.otsu_channel = SegmentationOptions::Channel::value;
  o.otsu_seed_is_high = true;
  const Segmentation v = segment(lit.image, o);
  ASSERT_TRUE(v.found) << v.reason;
  std::printf("[ info ] Otsu on V, evenly lit: threshold %.0f, IoU %.5f\n", v.threshold,
              intersection_over_union(v.mask, lit.mask));
  EXPECT_GT(intersection_over_union(v.mask, lit.mask), kMinIoU);
}

TEST(Segmentation, NoiseAloneIsNotASeed) {
  // A sphere far outside the field of view: the image is the background plus strong noise.
  Pose away;
  away.centre = {1000, 0, 0};
  RenderOptions o = photographic();
  o.noise_sigma = 12;
  const RenderedView view = render(Sphere(1, away), parallel_view(40), o);
  ASSERT_EQ(view.mask.area(), 0);
  const Segmentation s = segment(view.image);
  std::printf("[ info ] noise only: %s\n", s.reason.c_str());
  EXPECT_FALSE(s.found);
  EXPECT_FALSE(s.reason.empty());
  EXPECT_EQ(s.mask.area(), 0);
  EXPECT_EQ(s.mask.width(), 640);
}

TEST(Segmentation, TooSmallASeedIsReportedWithItsArea) {
  // A 1 mm ball at 40 px/mm: about pi 20^2 = 1,257 px, far below the 15,000 px minimum.
  const RenderedView view = render(Sphere(0.5), parallel_view(40), photographic());
  const Segmentation s = segment(view.image);
  std::printf("[ info ] small seed: %s\n", s.reason.c_str());
  EXPECT_FALSE(s.found);
  EXPECT_NE(s.reason.find("no contour with area in [15000, 50000] px; largest of 1 had "), std::string::npos)
      << s.reason;
  // The reported area is the contour polygon's, through the boundary pixels' centres: about
  // pi (20 - 1/2)^2 = 1,195 px; 5% either way covers the pixelisation of a 20 px disc.
  const auto at = s.reason.find(" had ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(s.reason.substr(at + 5)), 1195, 60) << s.reason;
  // With a range that admits it, it is found.
  SegmentationOptions small;
  small.min_area = 500;
  EXPECT_TRUE(segment(view.image, small).found);
}

TEST(Segmentation, FilesOverlaysAndErrorsNameTheirPaths) {
  const auto dir = scratch_dir();
  const RenderedView view = render(wheat(), parallel_view(40), photographic());
  const auto image_path = dir / "wheat.png";
  write_png(image_path, view.image);
  const cv::Mat back = read_image(image_path);
  EXPECT_EQ(cv::norm(back, view.image, cv::NORM_INF), 0.0);  // PNG is lossless
  const Segmentation s = segment_file(image_path);
  ASSERT_TRUE(s.found);

  const auto overlay = dir / "wheat_overlay.png";
  write_overlay(overlay, view.image, s, {{{100, 10}, {100, 470}}, {{540.5, 10}, {540.5, 470}}});
  const cv::Mat drawn = cv::imread(overlay.string());
  ASSERT_FALSE(drawn.empty());
  EXPECT_EQ(drawn.size(), view.image.size());
  EXPECT_EQ(drawn.at<cv::Vec3b>(s.contour.front()), cv::Vec3b(0, 255, 0));  // the contour is green
  EXPECT_EQ(drawn.at<cv::Vec3b>(240, 100), cv::Vec3b(0, 0, 255));           // a red line

  const auto garbage = dir / "not_an_image.png";
  std::ofstream(garbage) << "this is not a PNG";
  EXPECT_NE(testing::input_error_of([&] { read_image(garbage); }).find(garbage.string()), std::string::npos);
  const auto missing = dir / "missing.png";
  EXPECT_NE(testing::input_error_of([&] { segment_file(missing); }).find(missing.string()), std::string::npos);
  const auto empty = dir / "empty.png";
  std::ofstream{empty};
  EXPECT_NE(testing::input_error_of([&] { read_image(empty); }).find(empty.string()), std::string::npos);
  const auto unwritable = dir / "no_such_folder" / "overlay.png";
  EXPECT_NE(testing::input_error_of([&] { write_overlay(unwritable, view.image, s); }).find(unwritable.string()),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { segment(cv::Mat()); }).find("empty"), std::string::npos);
}

TEST(Segmentation, BadOptionsNameTheOption) {
  const cv::Mat image(10, 10, CV_8UC3, cv::Scalar(38, 15, 10));
  SegmentationOptions o;
  o.hsv_low[1] = 200;
  o.hsv_high[1] = 100;
  EXPECT_NE(testing::input_error_of([&] { segment(image, o); }).find("hsv_low S = 200"), std::string::npos);
  o = {};
  o.hsv_high[0] = 181;
  EXPECT_NE(testing::input_error_of([&] { segment(image, o); }).find("hsv_high H = 181"), std::string::npos);
  o = {};
  o.min_area = 100;
  o.max_area = 50;
  EXPECT_NE(testing::input_error_of([&] { segment(image, o); }).find("min_area = 100"), std::string::npos);
  o = {};
  o.open_kernel_px = -1;
  EXPECT_NE(testing::input_error_of([&] { segment(image, o); }).find("open_kernel_px = -1"), std::string::npos);
}

}  // namespace
}  // namespace suite::carving
