// Tests of the two-view slicing model on rendered silhouettes of a wheat-sized ellipsoid
// (7.2 x 3.6 x 2.9 mm) and balls: volume accuracy and its convergence in the number of slices,
// the side camera's scale correction, the end-to-end path through segmentation, and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "carving/image/image_io.hpp"
#include "carving/image/segmentation.hpp"
#include "carving/measure/measure_seed.hpp"
#include "carving/measure/seed_profile.hpp"
#include "carving/render/render_scene.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "carving/slicing/two_view.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/mpi/comm.hpp"
#include "tests/support/test_dirs.hpp"

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

// What docs/carving.md says the slice count buys, over 8 sub-pixel positions of the wheat ellipsoid
// at 40 px/mm (benchmarks/carving/two_view_slices.cpp, 16 positions: +0.48% at N = 10, mean
// +0.00% [-0.13, +0.16] at N = 50, -0.01% at N = 400): the mean error follows the midpoint rule's
// +1/(2 N^2) while that is large (within 0.15% of +0.5% at N = 10: the pixels' share), from N = 50
// on the mean is within 0.1% of the truth and every position within 0.25% (the pixels' spread;
// 0.84% at every N before the tips were found from the chords), and 100 or 400 slices move the
// mean by less than 0.05%: more slices buy nothing there. Averaging does not change that.
TEST(TwoView, SliceCountBuysWhatTheDocsSay) {
  constexpr int kPositions = 8;
  std::vector<Pair> pairs;
  for (int k = 0; k < kPositions; ++k) {
    Pose pose = lying_flat();
    const auto frac = [](double x) { return x - std::floor(x); };
    pose.centre =
        Eigen::Vector3d((k + 0.5) / kPositions, frac(0.6180339887 * k + 0.13), frac(0.7548776662 * k + 0.41)) / 40;
    const Ellipsoid seed(3.6, 1.8, 1.45, pose);
    pairs.push_back({render(seed, top_view(40)).mask, render(seed, side_view(40)).mask});
  }
  for (const bool average : {false, true}) {
    std::vector<double> means;
    for (const int n : {10, 50, 100, 400}) {
      SlicingOptions o;
      o.px_per_mm_top = 40;
      o.slices = n;
      o.neighbour_average = average;
      double mean = 0, worst = 0;
      for (const Pair& p : pairs) {
        const double e = measure_two_view(p.top, p.side, o).volume_mm3 / kWheatVolume - 1;
        mean += e / kPositions, worst = std::max(worst, std::abs(e));
      }
      std::printf("[ info ] %s N = %3d: mean error %+.3f%%, worst %.3f%%\n", average ? "averaged" : "plain   ", n,
                  100 * mean, 100 * worst);
      if (n == 10) {
        EXPECT_NEAR(mean, 1 / (2.0 * n * n), 0.0015) << average;
      }
      if (n >= 50) {
        EXPECT_LT(std::abs(mean), 0.001) << n << " " << average;
        EXPECT_LT(worst, 0.0025) << n << " " << average;
      }
      means.push_back(mean);
    }
    EXPECT_LT(std::abs(means[2] - means[1]), 0.0005) << average;
    EXPECT_LT(std::abs(means[3] - means[1]), 0.0005) << average;
  }
}

// --- The dissertation's neighbour averaging (SlicingOptions::neighbour_average) ---

// On a smooth convex outline the 5-column average is a box filter of variance 2 px^2 on each
// contour point, so a chord w(x) moves by about w''(x) * 1 px^2, downwards where the chord profile
// is concave. For an ellipsoid (A = a f, B = b f, f = sqrt(1 - x^2/L^2), L the half length in px)
// the volume then changes by -2 int f f'' / int f^2 = -1.5 ln(2/eps) / L^2 with the tips cut at
// eps ~ 2/L, where the expansion fails: -1.5 ln(L) / L^2. It is never positive on a convex
// outline away from the tips (the average of a concave function lies below it). Bound: twice the
// estimate, the second half for the tips and the pixels. Measured (benchmarks/results/carving/
// two_view_slices.md): -0.03% on the wheat grain, -0.09% on the 3.18 mm ball at 40 px/mm.
TEST(TwoView, NeighbourAveragingOfASmoothConvexOutlineChangesTheVolumeLittle) {
  struct Case {
    const char* name;
    double half_length_px;
    Pair masks;
    double true_mm3;
  };
  const Sphere small_ball(3.18 / 2, lying_flat());
  const std::vector<Case> cases{{"wheat ellipsoid", 3.6 * 40, wheat_masks(40, 40), kWheatVolume},
                                {"3.18 mm ball",
                                 1.59 * 40,
                                 {render(small_ball, top_view(40)).mask, render(small_ball, side_view(40)).mask},
                                 small_ball.volume()}};
  for (const Case& c : cases) {
    SlicingOptions o;
    o.px_per_mm_top = 40;
    o.slices = 200;  // dense slices: the volume integrates the averaged chords
    const double plain = measure_two_view(c.masks.top, c.masks.side, o).volume_mm3;
    o.neighbour_average = true;
    const TwoViewResult averaged = measure_two_view(c.masks.top, c.masks.side, o);
    const double change = averaged.volume_mm3 / plain - 1;
    const double estimate = -1.5 * std::log(c.half_length_px) / (c.half_length_px * c.half_length_px);
    std::printf("[ info ] %s: averaging changes V by %+.4f%% (estimate %+.4f%%); error %+.3f%% -> %+.3f%%\n", c.name,
                100 * change, 100 * estimate, 100 * (plain / c.true_mm3 - 1),
                100 * (averaged.volume_mm3 / c.true_mm3 - 1));
    EXPECT_LT(change, 0) << c.name;
    EXPECT_GT(change, 2 * estimate) << c.name;
    EXPECT_LT(std::abs(averaged.volume_mm3 / c.true_mm3 - 1), kVolumeTolerance) << c.name;
  }
}

// A one-column spike on the top view's outline (a hair, a speck stuck to the seed: 12 px tall,
// 1 px wide) at the column nearest a slice centre. Without averaging the slice's chord takes the
// spike at its full height (times 1 - d, d the slice centre's distance from the column), and the
// slice counts it over its whole length h = 5.76 px: 5.76 times the spike's own area. With
// averaging the spike's column shares its upper point with the two columns on each side, so every
// chord within 2 columns grows by exactly 12/5 px and the slice takes a fifth of the spike: the
// volume change is exactly 1 / (5 (1 - d)) of the plain one, and the spike enters at
// h / 5 = 1.15 times its own area instead of 5.76 times.
TEST(TwoView, NeighbourAveragingTakesAFifthOfAOneColumnSpike) {
  const Pair clean = wheat_masks(40, 40);
  SlicingOptions o;
  o.px_per_mm_top = 40;
  const TwoViewResult plain_clean = measure_two_view(clean.top, clean.side, o);
  const Slice& target = plain_clean.slices[20];
  const int column = static_cast<int>(std::lround(target.top_x_px));
  const double d = std::abs(target.top_x_px - column);
  std::vector<std::uint8_t> pixels = clean.top.pixels();
  int upper = 0;
  while (!clean.top.at(column, upper)) ++upper;
  constexpr int kSpikePx = 12;
  for (int y = upper - kSpikePx; y < upper; ++y) pixels[static_cast<std::size_t>(y) * clean.top.width() + column] = 1;
  const Mask spiked(clean.top.width(), clean.top.height(), std::move(pixels));

  const double plain_change = measure_two_view(spiked, clean.side, o).volume_mm3 - plain_clean.volume_mm3;
  o.neighbour_average = true;
  const double averaged_change =
      measure_two_view(spiked, clean.side, o).volume_mm3 - measure_two_view(clean.top, clean.side, o).volume_mm3;
  // The spike's own volume in the elliptic model: its width over one column, at this slice's B.
  const double own = pi * (0.5 * kSpikePx / 40) * target.b_mm * (1.0 / 40);
  std::printf(
      "[ info ] spike of %d px at %.2f px from slice 20's centre: V +%.5f mm^3 plain (%.2f x its own), "
      "+%.5f mm^3 averaged (%.2f x)\n",
      kSpikePx, d, plain_change, plain_change / own, averaged_change, averaged_change / own);
  EXPECT_NEAR(plain_change, own * target.h_mm * 40 * (1 - d), 1e-9);
  EXPECT_NEAR(averaged_change, plain_change / (5 * (1 - d)), 1e-9);
  EXPECT_NEAR(averaged_change / own, target.h_mm * 40 / 5, 1e-6);
}

// The option from the profile key through measure_seed: the rendered two-view photographs of
// carving/examples/synthetic/wheat_two_view.yaml measured with the profile `seedcarve render` wrote,
// plain and with the command line's `slicing.neighbour_average=true`; seed.json says which, and
// the volume is measure_two_view's on the same segmented images with the option set.
TEST(TwoView, NeighbourAveragingFromTheProfileEndToEnd) {
  const mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = testing::scratch_dir(world);
  render_scene(config::Config::from_file(SUITE_SOURCE_DIR "/carving/examples/synthetic/wheat_two_view.yaml"),
               dir / "images");
  const auto profile_file = dir / "images" / "profile.yaml";
  const SeedProfile plain = read_seed_profile(config::Config::from_file(profile_file));
  const SeedProfile averaged =
      read_seed_profile(config::Config::from_file(profile_file, {"slicing.neighbour_average=true"}));
  EXPECT_FALSE(plain.slicing.neighbour_average);  // off by default
  ASSERT_TRUE(averaged.slicing.neighbour_average);
  EXPECT_NE(averaged.effective_yaml.find("neighbour_average: true"), std::string::npos) << averaged.effective_yaml;

  const SeedEntry seed{"wheat", {dir / "images" / "top.png", dir / "images" / "side.png"}, "slicing", {}, {}};
  const SeedRow a = measure_seed(seed, plain, dir / "plain"), b = measure_seed(seed, averaged, dir / "averaged");
  ASSERT_TRUE(a.ok) << a.message;
  ASSERT_TRUE(b.ok) << b.message;
  EXPECT_NE(testing::read_file(dir / "averaged" / "seed.json").find("\"neighbour_average\": true"), std::string::npos);
  EXPECT_NE(testing::read_file(dir / "plain" / "seed.json").find("\"neighbour_average\": false"), std::string::npos);

  const Segmentation top = segment(read_image(dir / "images" / "top.png"), averaged.segmentation);
  const Segmentation side = segment(read_image(dir / "images" / "side.png"), averaged.segmentation);
  ASSERT_TRUE(top.found && side.found);
  EXPECT_DOUBLE_EQ(b.volume_mm3, measure_two_view(top.mask, side.mask, averaged.slicing).volume_mm3);
  EXPECT_DOUBLE_EQ(a.volume_mm3, measure_two_view(top.mask, side.mask, plain.slicing).volume_mm3);
  EXPECT_NE(a.volume_mm3, b.volume_mm3);
  std::printf("[ info ] rendered wheat photographs: V %.4f mm^3 plain, %.4f averaged (%+.3f%%)\n", a.volume_mm3,
              b.volume_mm3, 100 * (b.volume_mm3 / a.volume_mm3 - 1));
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
