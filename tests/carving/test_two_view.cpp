// Tests of the two-view slicing model on rendered silhouettes of a wheat-sized ellipsoid
// (7.2 x 3.6 x 2.9 mm) and balls: volume accuracy and its convergence in the number of slices,
// the side camera's scale correction, the end-to-end path through segmentation, and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "carving/image/segmentation.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "carving/slicing/two_view.hpp"
#include "core/errors.hpp"

namespace suite::carving {
namespace {

constexpr double pi = std::numbers::pi;

// The seed lies on a table: long axis along world x, width along world z, thickness along world y
// (vertical; y is "down" as on the turntable). The centre is off the pixel grid on purpose.
Pose lying_flat() {
  Pose pose;
  pose.rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // body x -> world x, body y -> world z, body z -> world -y
  pose.centre = {0.0123, 0.0171, -0.0093};
  return pose;
}

// Top camera, parallel projection looking down (+y): u = s x + width/2, v = -s z + height/2; the
// seed's long axis is the image x axis and its width the image y axis.
View top_view(double scale, int width = 640, int height = 480) {
  View v;
  v.P << scale, 0, 0, width / 2.0, 0, 0, -scale, height / 2.0, 0, 0, 0, 1;
  v.width = width;
  v.height = height;
  return v;
}

// Side camera, parallel projection looking along +z: u = s x + width/2 - 20, v = s y + height/2 + 10;
// long axis along the image x axis, thickness along the image y axis.
View side_view(double scale, int width = 640, int height = 480) {
  View v;
  v.P << scale, 0, 0, width / 2.0 - 20, 0, scale, 0, height / 2.0 + 10, 0, 0, 0, 1;
  v.width = width;
  v.height = height;
  return v;
}

struct Pair {
  Mask top, side;
};

Pair wheat_masks(double top_scale, double side_scale, int width = 640, int height = 480) {
  const Ellipsoid seed(3.6, 1.8, 1.45, lying_flat());
  return {render(seed, top_view(top_scale, width, height)).mask,
          render(seed, side_view(side_scale, width, height)).mask};
}

constexpr double kWheatVolume = 4.0 / 3.0 * pi * 3.6 * 1.8 * 1.45;

// The target of docs/methods/carving.md (below 3% on balls once N >= 50) tightened to the 1% asked of this model on
// clean silhouettes at 40 px/mm; the pixel error alone is about 1 px on 116-288 px (0.3-0.9%) per
// extent and averages out over the slices' areas.
constexpr double kVolumeTolerance = 0.01;
constexpr double kThicknessTolerance = 0.01;

// For an ellipsoid the slice areas pi A(x) B(x) are a quadratic in x, so the midpoint rule's error
// is exactly h^2/24 * |f''| * length = +1/(2 N^2) of the volume (h = length / N): +0.5% at N = 10,
// +0.125% at 20, +0.02% at 50, +0.005% at 100. On top of it comes the pixelisation: each slice's
// width and thickness are pixel counts (+-1 px on 116-144 px), an error that averages over the
// slices, so it too shrinks as N grows.
std::vector<double> volume_errors(const Pair& m, double scale, const std::vector<int>& slices) {
  std::vector<double> errors;
  for (int n : slices) {
    SlicingOptions o;
    o.slices = n;
    o.px_per_mm_top = scale;
    const TwoViewResult r = measure_two_view(m.top, m.side, o);
    EXPECT_EQ(r.slices.size(), static_cast<std::size_t>(n));
    errors.push_back(r.volume_mm3 / kWheatVolume - 1);
    std::printf(
        "[ info ] %.0f px/mm, N = %3d: V = %.4f mm^3 (true %.4f), error %+.4f%%, midpoint-rule term "
        "1/(2N^2) = %+.4f%%, rest %+.4f%%; L %.4f W %.4f T %.4f mm\n",
        scale, n, r.volume_mm3, kWheatVolume, 100 * errors.back(), 100 / (2.0 * n * n),
        100 * (errors.back() - 1 / (2.0 * n * n)), r.length_mm, r.width_mm, r.thickness_mm);
  }
  return errors;
}

TEST(TwoView, WheatEllipsoidVolumeConvergesWithTheNumberOfSlices) {
  const std::vector<int> slices{10, 20, 50, 100, 200};
  const std::vector<double> errors = volume_errors(wheat_masks(40, 40), 40, slices);
  for (std::size_t k = 0; k < slices.size(); ++k) {
    if (slices[k] >= 50) {
      EXPECT_LT(std::abs(errors[k]), kVolumeTolerance) << "N = " << slices[k];
    }
    if (k > 0) {
      EXPECT_LT(std::abs(errors[k]), std::abs(errors[k - 1])) << "N = " << slices[k];
    }
  }
  // What is left after the midpoint term is the pixel error: measured 0.29% at N = 10 (10 slices
  // average little), 0.1% at N = 50 and below; 0.4% bounds it at every N.
  constexpr double kPixelError40 = 0.004;
  for (std::size_t k = 0; k < slices.size(); ++k)
    EXPECT_NEAR(errors[k], 1 / (2.0 * slices[k] * slices[k]), kPixelError40) << "N = " << slices[k];
}

TEST(TwoView, MidpointRuleErrorIsOneOverTwoNSquaredAtHighResolution) {
  // At 200 px/mm (a 1440 x 720 px top silhouette) the pixel error is 5x smaller, and the error
  // follows the midpoint term 1/(2 N^2) closely: its 4x drop from N = 10 to 20 shows the O(1/N^2).
  // The pixel part measured +0.037%, +0.034%, +0.004% at N = 10, 20, 50; 0.06% bounds it (and is
  // below the 0.08% that one fifth of the 40 px/mm bound would give).
  constexpr double kPixelError200 = 0.0006;
  const std::vector<int> slices{10, 20, 50};
  const std::vector<double> errors = volume_errors(wheat_masks(200, 200, 1600, 800), 200, slices);
  for (std::size_t k = 0; k < slices.size(); ++k)
    EXPECT_NEAR(errors[k], 1 / (2.0 * slices[k] * slices[k]), kPixelError200) << "N = " << slices[k];
}

TEST(TwoView, ScaleCorrectionRecoversTheSideCamerasDistance) {
  // The side camera is farther away: 35 px/mm against the top camera's 40.
  const Pair m = wheat_masks(40, 35);
  SlicingOptions o;
  o.px_per_mm_top = 40;
  const TwoViewResult r = measure_two_view(m.top, m.side, o);
  std::printf(
      "[ info ] side at 35 px/mm, corrected: s = %.5f (true %.5f), T = %.4f mm (true 2.9, %+.3f%%), "
      "V error %+.3f%%\n",
      r.scale, 40.0 / 35.0, r.thickness_mm, 100 * (r.thickness_mm / 2.9 - 1), 100 * (r.volume_mm3 / kWheatVolume - 1));
  EXPECT_NEAR(r.thickness_mm / 2.9, 1, kThicknessTolerance);
  EXPECT_NEAR(r.volume_mm3 / kWheatVolume, 1, kVolumeTolerance);
  EXPECT_NEAR(r.px_per_mm_side, 35, 35 * kThicknessTolerance);

  o.scale_correction = false;
  const TwoViewResult raw = measure_two_view(m.top, m.side, o);
  std::printf("[ info ] side at 35 px/mm, uncorrected: T = %.4f mm (%+.2f%%), V error %+.2f%%\n", raw.thickness_mm,
              100 * (raw.thickness_mm / 2.9 - 1), 100 * (raw.volume_mm3 / kWheatVolume - 1));
  EXPECT_EQ(raw.scale, 1.0);
  // Without it the thickness shrinks by 35/40: -12.5%.
  EXPECT_NEAR(raw.thickness_mm / 2.9, 35.0 / 40.0, kThicknessTolerance);
}

TEST(TwoView, LengthWidthThicknessAndSlices) {
  const Pair m = wheat_masks(40, 40);
  SlicingOptions o;
  o.px_per_mm_top = 40;
  const TwoViewResult r = measure_two_view(m.top, m.side, o);
  // Extents count pixel columns/rows whose centres are inside: within 1 px of the true size.
  constexpr double kOnePixelMm = 1.0 / 40;
  EXPECT_NEAR(r.length_mm, 7.2, kOnePixelMm);
  EXPECT_NEAR(r.width_mm, 3.6, kOnePixelMm);
  EXPECT_NEAR(r.thickness_mm, 2.9, kOnePixelMm);
  double sum = 0, length = 0;
  for (const Slice& s : r.slices) {
    sum += s.volume_mm3;
    length += s.h_mm;
    EXPECT_NEAR(s.volume_mm3, pi * s.a_mm * s.b_mm * s.h_mm, 1e-12);
    EXPECT_GE(s.top_x_px, r.top_box.x0 - 0.5);
    EXPECT_LE(s.top_x_px, r.top_box.x1 + 0.5);
  }
  EXPECT_NEAR(sum, r.volume_mm3, 1e-9);
  EXPECT_NEAR(length, r.length_mm, 1e-12);
  // The middle slice is at the widest point: A and B close to the semi-axes.
  const Slice& middle = r.slices[25];
  EXPECT_NEAR(middle.a_mm, 1.8, kOnePixelMm);
  EXPECT_NEAR(middle.b_mm, 1.45, kOnePixelMm);
}

// The seed's centre on a pixel centre (a whole-pixel principal point): its tips then fall exactly
// on pixel centres, and counting the columns and rows with seed pixels read every dimension 1 px
// long (7.225 x 3.625 x 2.925 mm at 40 px/mm). The tips from the chord lengths of the last two
// lines (two_view.cpp, ends()) read them within a fifth of a pixel at any position of the seed.
TEST(TwoView, DimensionsWithoutThePixelBiasAtAnyPosition) {
  for (const double offset : {0.0, 0.25 / 40, 0.5 / 40, 0.0123}) {
    Pose pose = lying_flat();
    pose.centre = {offset, 0.0, -offset};
    const Ellipsoid seed(3.6, 1.8, 1.45, pose);
    SlicingOptions o;
    o.px_per_mm_top = 40;
    o.slices = 200;
    const TwoViewResult r = measure_two_view(render(seed, top_view(40)).mask, render(seed, side_view(40)).mask, o);
    std::printf("[ info ] centre %+.4f mm: L %.4f W %.4f T %.4f mm, V error %+.3f%%\n", offset, r.length_mm, r.width_mm,
                r.thickness_mm, 100 * (r.volume_mm3 / kWheatVolume - 1));
    constexpr double kFifthPixelMm = 0.2 / 40;
    EXPECT_NEAR(r.length_mm, 7.2, kFifthPixelMm) << offset;
    EXPECT_NEAR(r.width_mm, 3.6, kFifthPixelMm) << offset;
    EXPECT_NEAR(r.thickness_mm, 2.9, kFifthPixelMm) << offset;
    // The volume: the chords are whole pixel counts (+-1 px on 116-144 px), which stay in phase
    // along the seed when its centre sits on a pixel centre: measured -0.25% there, within 0.12%
    // elsewhere (it was +0.84% at every slice count); 0.5%, half the model's 1% target.
    EXPECT_NEAR(r.volume_mm3, kWheatVolume, 0.005 * kWheatVolume) << offset;
  }
}

TEST(TwoView, BallsAsInTheDissertation) {
  // 3.18 mm and 6.35 mm balls (the dissertation's check: below 3% at N >= 50), at 40 px/mm top and
  // 35 px/mm side.
  for (double diameter : {3.18, 6.35}) {
    const Sphere ball(diameter / 2, lying_flat());
    SlicingOptions o;
    o.px_per_mm_top = 40;
    const TwoViewResult r = measure_two_view(render(ball, top_view(40)).mask, render(ball, side_view(35)).mask, o);
    const double error = r.volume_mm3 / ball.volume() - 1;
    std::printf("[ info ] ball %.2f mm: V = %.4f mm^3 (true %.4f), error %+.3f%%\n", diameter, r.volume_mm3,
                ball.volume(), 100 * error);
    EXPECT_LT(std::abs(error), kVolumeTolerance);
  }
}

TEST(TwoView, EndToEndFromRenderedPhotographs) {
  // Colour images with blur and noise, segmented, then sliced. The segmented outline sits a fraction
  // of a pixel outside the exact one: the seed is far brighter than the background, so an edge pixel
  // takes the seed's hue from well below half coverage. Half a pixel all round would add
  // 1/144 (width) + 1/101.5 (thickness at 35 px/mm) + 1/288 (length) = 2.0% to the volume; measured
  // +1.1% with the HSV range and +1.9% with Otsu on hue; 2.5% bounds it with margin for the noise.
  constexpr double kEndToEndTolerance = 0.025;
  const Ellipsoid seed(3.6, 1.8, 1.45, lying_flat());
  RenderOptions photo;
  photo.supersampling = 4;
  photo.blur_sigma_px = 1.0;
  photo.noise_sigma = 4;
  const RenderedView top = render(seed, top_view(40), photo);
  photo.noise_seed = 2;
  const RenderedView side = render(seed, side_view(35), photo);
  SegmentationOptions automatic;
  automatic.automatic = true;
  for (const SegmentationOptions& so : {SegmentationOptions{}, automatic}) {
    const Segmentation st = segment(top.image, so), ss = segment(side.image, so);
    ASSERT_TRUE(st.found) << st.reason;
    ASSERT_TRUE(ss.found) << ss.reason;
    SlicingOptions o;
    o.px_per_mm_top = 40;
    const TwoViewResult r = measure_two_view(st.mask, ss.mask, o);
    std::printf("[ info ] end to end (%s): V error %+.3f%%, L %.4f W %.4f T %.4f mm\n",
                so.automatic ? "Otsu on H" : "HSV range", 100 * (r.volume_mm3 / kWheatVolume - 1), r.length_mm,
                r.width_mm, r.thickness_mm);
    EXPECT_NEAR(r.volume_mm3 / kWheatVolume, 1, kEndToEndTolerance);
  }
}

TEST(TwoView, InputErrorsAndDensity) {
  const Pair m = wheat_masks(40, 40);
  const auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  SlicingOptions o;
  o.px_per_mm_top = 40;
  const Mask empty(640, 480, std::vector<std::uint8_t>(640 * 480, 0));
  EXPECT_NE(message([&] { measure_two_view(empty, m.side, o); }).find("top-view mask is empty"), std::string::npos);
  EXPECT_NE(message([&] { measure_two_view(m.top, Mask(), o); }).find("side-view mask is empty"), std::string::npos);
  SlicingOptions no_scale;
  EXPECT_NE(message([&] { measure_two_view(m.top, m.side, no_scale); }).find("px_per_mm_top = 0"), std::string::npos);
  SlicingOptions no_slices = o;
  no_slices.slices = 0;
  EXPECT_NE(message([&] { measure_two_view(m.top, m.side, no_slices); }).find("slices = 0"), std::string::npos);

  EXPECT_DOUBLE_EQ(density_mg_per_mm3(52.0, 40.0), 1.3);
  EXPECT_NE(message([] { density_mg_per_mm3(-1, 40); }).find("weight = -1"), std::string::npos);
  EXPECT_NE(message([] { density_mg_per_mm3(50, 0); }).find("volume = 0"), std::string::npos);
}

}  // namespace
}  // namespace suite::carving
