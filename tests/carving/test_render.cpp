// Tests of the analytic seed shapes (volumes, inside tests, ray hits, normals) and of the renderer
// (exact silhouettes of a sphere under parallel and central projection, colours, noise, options).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "core/errors.hpp"

namespace suite::carving {
namespace {

constexpr double pi = std::numbers::pi;

// Volume of Barr's superellipsoid by the midpoint rule on an n x n grid of the first quadrant of
// the x-y box, integrating the exact z-chord 2c (1 - G)^(e1/2), G = (x'^(2/e2) + y'^(2/e2))^(e2/e1).
double superellipsoid_volume_by_quadrature(double a, double b, double c, double e1, double e2, int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n;
    const double px = std::pow(x, 2 / e2);
    for (int j = 0; j < n; ++j) {
      const double y = (j + 0.5) / n;
      const double G = std::pow(px + std::pow(y, 2 / e2), e2 / e1);
      if (G < 1) sum += 2 * std::pow(1 - G, e1 / 2);
    }
  }
  return 4 * a * b * c * sum / (static_cast<double>(n) * n);
}

// Fraction of `samples` uniform points of the bounding box [-a, a] x [-b, b] x [-c, c] inside `shape`
// (identity pose), times the box volume; the second value is one standard deviation.
std::pair<double, double> monte_carlo_volume(const Shape& shape, const Eigen::Vector3d& half, int samples,
                                             std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  long long inside = 0;
  for (int k = 0; k < samples; ++k)
    inside += shape.contains(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(half));
  const double box = 8 * half.prod(), p = static_cast<double>(inside) / samples;
  return {p * box, box * std::sqrt(p * (1 - p) / samples)};
}

TEST(Shapes, SuperellipsoidVolumeFormulaMatchesQuadrature) {
  // Midpoint rule on 2000 x 2000 cells: the integrand is smooth inside and behaves like
  // (1 - G)^(e1/2) at the rim, so the rim cells give a relative error O(h^(1 + e1/2)) at worst,
  // h = 1/2000; observed at most 1.8e-6 over these exponents. 2e-5 is 10x that and far below
  // any slip in the Beta-function formula (a wrong argument changes the volume by > 1%).
  constexpr double kRelativeTolerance = 2e-5;
  constexpr int kCells = 2000;
  const double a = 3.6, b = 1.8, c = 1.45;
  for (const auto& [e1, e2] :
       std::vector<std::pair<double, double>>{{1, 1}, {0.3, 1.2}, {0.6, 0.6}, {1.5, 0.7}, {2, 2}, {3, 2.5}}) {
    const Superellipsoid shape(a, b, c, e1, e2);
    const double quadrature = superellipsoid_volume_by_quadrature(a, b, c, e1, e2, kCells);
    const double relative = shape.volume() / quadrature - 1;
    std::printf("[ info ] superellipsoid e1 = %.1f e2 = %.1f: formula %.6f mm^3, quadrature %.6f, rel. diff %.2e\n", e1,
                e2, shape.volume(), quadrature, relative);
    EXPECT_NEAR(relative, 0, kRelativeTolerance) << "e1 = " << e1 << ", e2 = " << e2;
  }
  // e1 = e2 = 1 is the ellipsoid.
  EXPECT_NEAR(Superellipsoid(a, b, c, 1, 1).volume(), Ellipsoid(a, b, c).volume(), 1e-12 * Ellipsoid(a, b, c).volume());
}

TEST(Shapes, ContainsAgreesWithVolumeByMonteCarlo) {
  // 400,000 uniform points: the estimate's standard deviation sigma is computed from the sample;
  // 4 sigma leaves a 6e-5 chance of a false failure per shape (the seed is fixed, so the run is
  // deterministic anyway).
  constexpr double kSigmas = 4;
  constexpr int kSamples = 400000;
  const Superellipsoid super(3.6, 1.8, 1.45, 0.5, 1.5);
  const CreasedGrain grain(3.6, 1.8, 1.45, 0.3, 0.7);
  const Ellipsoid ellipsoid(3.6, 1.8, 1.45);
  for (const Shape* shape : std::vector<const Shape*>{&super, &grain, &ellipsoid}) {
    const auto [estimate, sigma] = monte_carlo_volume(*shape, {3.6, 1.8, 1.45}, kSamples, 12345);
    std::printf("[ info ] %s: volume %.5f mm^3, Monte Carlo %.5f +- %.5f\n", shape->name().c_str(), shape->volume(),
                estimate, sigma);
    EXPECT_NEAR(estimate, shape->volume(), kSigmas * sigma) << shape->name();
  }
}

TEST(Shapes, CreasedGrainVolumeIsBelowItsEllipsoidAndConverged) {
  const double a = 3.6, b = 1.8, c = 1.45;
  const CreasedGrain coarse(a, b, c, 0.3, 0.7, {}, 1e-6), fine(a, b, c, 0.3, 0.7, {}, 1e-11);
  const double groove = fine.ellipsoid_volume() - fine.volume();
  std::printf(
      "[ info ] creased grain: ellipsoid %.9f, grain %.9f mm^3 (groove %.6f, %.2f%%), error estimate %.1e; "
      "at tolerance 1e-6: %.9f\n",
      fine.ellipsoid_volume(), fine.volume(), groove, 100 * groove / fine.ellipsoid_volume(),
      fine.volume_error_estimate(), coarse.volume());
  EXPECT_LT(fine.volume(), fine.ellipsoid_volume());
  // The slot, 0.6 mm wide and 0.7 mm deep at the middle and fading out towards the ends, removes
  // less than a full-length slot of that cross-section (a half disc on a 0.4 x 0.6 mm rectangle).
  EXPECT_GT(groove, 0.1);
  EXPECT_LT(groove, 2 * a * (pi * 0.3 * 0.3 / 2 + 0.4 * 0.6));
  // Each quadrature meets its own tolerance, and they agree within the looser one.
  EXPECT_LE(coarse.volume_error_estimate(), 1e-6);
  EXPECT_LE(fine.volume_error_estimate(), 1e-11);
  EXPECT_NEAR(coarse.volume(), fine.volume(), 1e-6);

  // An independent check: the midpoint rule over a 3000 x 3000 grid of the (x, y) box of the
  // public chord function. Its error comes from the cells cut by the rim and by the groove's
  // edges, where the chord has square-root behaviour: measured -1.8e-5, -1.0e-5, -5.6e-6, -2.1e-6
  // mm^3 at 750, 1500, 3000, 6000 cells a side (order h^0.8-1.4, heading to the quadrature value),
  // so 3e-5 mm^3 (8e-7 of the volume) bounds the 3000-cell error with margin.
  constexpr double kMidpointTolerance = 3e-5;
  constexpr int kCells = 3000;
  double sum = 0;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) sum += fine.chord_length_z(a * ((i + 0.5) / kCells), b * ((j + 0.5) / kCells));
  const double midpoint = 4 * a * b * sum / (static_cast<double>(kCells) * kCells);
  std::printf("[ info ] creased grain by 3000^2 midpoint rule: %.9f (diff %.2e)\n", midpoint, midpoint - fine.volume());
  EXPECT_NEAR(midpoint, fine.volume(), kMidpointTolerance);
}

// Rays from random points around the shape towards random points near it: a hit lies on the
// surface, no earlier point of the ray is inside, the normal points outwards; a miss has no point
// inside along the ray.
void check_rays(const Shape& shape, int rays, std::uint64_t seed) {
  // |implicit| at the returned point: the bisections stop at 1e-12 of the radius; the implicit
  // functions have slopes of order 1 (mm per mm), so 1e-9 mm is a loose bound.
  constexpr double kSurfaceTolerance = 1e-9;
  // Step back / forward along the normal for the normal test: small against curvature radii (> 0.3 mm).
  constexpr double kNormalStep = 1e-5;
  constexpr int kSamplesAlongRay = 4000;
  const BoundingSphere bounds = shape.bounding_sphere();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  const auto random_unit = [&] { return Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized(); };
  int hits = 0, normal_failures = 0;
  for (int k = 0; k < rays; ++k) {
    const Eigen::Vector3d origin = bounds.centre + 2.5 * bounds.radius * random_unit();
    // Aim half the rays near the centre (mostly hits), half beyond the bounding sphere (many misses).
    const Eigen::Vector3d target = bounds.centre + (k % 2 ? 0.3 : 1.3) * bounds.radius * random_unit();
    const Eigen::Vector3d d = (target - origin).normalized();
    const auto t = shape.first_hit(origin, 3.0 * d);  // the direction need not be a unit vector
    const double t_end = (bounds.centre - origin).norm() + bounds.radius;
    const double limit = t ? *t - 1e-7 : t_end;
    for (int i = 0; i < kSamplesAlongRay; ++i) {
      const double ti = limit * (i + 0.5) / kSamplesAlongRay;
      ASSERT_FALSE(shape.contains(origin + ti * d))
          << shape.name() << " ray " << k << " inside at " << ti << (t ? " before the hit" : " but first_hit missed");
    }
    if (!t) continue;
    ++hits;
    const Eigen::Vector3d X = origin + *t * d;
    EXPECT_NEAR(shape.implicit(X), 0, kSurfaceTolerance) << shape.name() << " ray " << k;
    const Eigen::Vector3d n = shape.normal(X);
    EXPECT_NEAR(n.norm(), 1, 1e-12);
    if (!(shape.implicit(X + kNormalStep * n) > 0 && shape.implicit(X - kNormalStep * n) < 0)) ++normal_failures;
  }
  std::printf("[ info ] %s: %d of %d rays hit, %d normals failed the in/out test\n", shape.name().c_str(), hits, rays,
              normal_failures);
  EXPECT_GT(hits, rays / 4) << shape.name();
  EXPECT_LT(hits, rays) << shape.name();
  EXPECT_EQ(normal_failures, 0) << shape.name();
}

TEST(Shapes, FirstHitConsistentWithContains) {
  Pose pose;
  pose.rotation = rotation_matrix({1, 2, 3}, 0.7);
  pose.centre = {0.3, -0.2, 5.0};
  check_rays(Sphere(1.9, pose), 400, 1);
  check_rays(Ellipsoid(3.6, 1.8, 1.45, pose), 400, 2);
  check_rays(Superellipsoid(3.6, 1.8, 1.45, 0.5, 1.5, pose), 400, 3);
  check_rays(Superellipsoid(3.6, 1.8, 1.45, 2.5, 3.0, pose), 200, 4);  // non-convex: the sampling path
  check_rays(CreasedGrain(3.6, 1.8, 1.45, 0.3, 0.7, pose), 400, 5);
}

TEST(Shapes, RayFromInsideHitsAtZeroAndBadInputIsRejected) {
  const Ellipsoid e(3.6, 1.8, 1.45);
  EXPECT_EQ(e.first_hit({0, 0, 0}, {1, 0, 0}).value_or(-1), 0.0);
  EXPECT_FALSE(e.first_hit({10, 0, 0}, {1, 0, 0}).has_value());  // pointing away
  EXPECT_NEAR(e.first_hit({10, 0, 0}, {-1, 0, 0}).value_or(-1), 10 - 3.6, 1e-12);
  const auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(message([] { Ellipsoid(-1, 1, 1); }).find("a = -1"), std::string::npos);
  EXPECT_NE(message([] { Superellipsoid(1, 1, 1, 0.05, 1); }).find("e1"), std::string::npos);
  EXPECT_NE(message([] { CreasedGrain(3.6, 1.8, 1.45, 0.3, 2.0); }).find("crease_depth"), std::string::npos);
  Pose mirrored;
  mirrored.rotation = Eigen::Vector3d(1, 1, -1).asDiagonal();
  EXPECT_NE(message([&] { Sphere(1, mirrored); }).find("rotation"), std::string::npos);
  EXPECT_NE(message([&] { e.first_hit({0, 0, 0}, {0, 0, 0}); }).find("zero"), std::string::npos);
}

// ------------------------------------------------------------------------------------ Renderer

// A parallel view with `scale` px/mm looking along +z (world x -> u, world y -> v).
View parallel_view(double scale, double cx, double cy, int width, int height) {
  View v;
  v.P << scale, 0, 0, cx, 0, scale, 0, cy, 0, 0, 0, 1;
  v.width = width;
  v.height = height;
  return v;
}

// Pixels whose centres lie inside a circle of radius R about (cx, cy), except that pixels within
// `band` of the circle are reported separately as ambiguous.
struct DiscCheck {
  long long mismatches = 0, ambiguous = 0;
};

DiscCheck compare_with_disc(const Mask& mask, double cx, double cy, double R, double band) {
  DiscCheck out;
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x) {
      const double r = std::hypot(x - cx, y - cy);
      if (std::abs(r - R) < band)
        ++out.ambiguous;
      else if (mask.at(x, y) != (r < R))
        ++out.mismatches;
    }
  return out;
}

// Pixel count of a pixelised disc: every pixel whose centre is inside lies within R + sqrt(2)/2 of
// the centre and every point within R - sqrt(2)/2 lies in such a pixel, so
// pi (R - sqrt(2)/2)^2 <= count <= pi (R + sqrt(2)/2)^2, i.e. |count - pi R^2| <= pi (sqrt(2) R + 1/2):
// the perimeter times sqrt(2)/2, plus a constant.
double disc_count_bound(double R) {
  return pi * (std::sqrt(2.0) * R + 0.5);
}

// Pixels closer than this to the analytic circle are not compared: the ray hit is exact to about
// 1e-12 mm, i.e. far below 1e-6 px, so only rounding-level ties are excluded.
constexpr double kTieBandPx = 1e-6;

TEST(Renderer, SphereUnderParallelProjectionIsTheExactDisc) {
  const double scale = 40, r = 2.5075;  // R = 100.3 px
  Pose pose;
  pose.centre = {0.0123, -0.0071, 3.0};
  const Sphere sphere(r, pose);
  const View view = parallel_view(scale, 320, 240, 640, 480);
  const RenderedView out = render(sphere, view);
  const double R = scale * r, cx = 320 + scale * pose.centre.x(), cy = 240 + scale * pose.centre.y();
  const DiscCheck check = compare_with_disc(out.mask, cx, cy, R, kTieBandPx);
  const double deviation = static_cast<double>(out.mask.area()) - pi * R * R;
  std::printf("[ info ] parallel sphere: %lld px, pi R^2 = %.1f, deviation %.1f (bound %.1f), mismatches %lld\n",
              out.mask.area(), pi * R * R, deviation, disc_count_bound(R), check.mismatches);
  EXPECT_EQ(check.mismatches, 0);
  EXPECT_LE(std::abs(deviation), disc_count_bound(R));
}

TEST(Renderer, SphereOnTheAxisOfAPinholeCameraIsTheDiscOfAngularRadius) {
  // Sphere of radius r at distance d on the optical axis: its silhouette is the cone of half-angle
  // asin(r / d), i.e. the disc of radius f tan(asin(r / d)) about the principal point.
  const double f = 4000, d = 100, r = 2.0;
  Intrinsics K{f, 320.37, 240.21};
  const Turntable rig{K, d, 1, 0.0, 0.0, 640, 480};
  const View view = rig.all_views().front();
  const Sphere sphere(r);
  const RenderedView out = render(sphere, view);
  const double R = f * std::tan(std::asin(r / d));
  const DiscCheck check = compare_with_disc(out.mask, K.cx, K.cy, R, kTieBandPx);
  const double deviation = static_cast<double>(out.mask.area()) - pi * R * R;
  std::printf(
      "[ info ] pinhole sphere: R = %.3f px, %lld px, pi R^2 = %.1f, deviation %.1f (bound %.1f), "
      "mismatches %lld\n",
      R, out.mask.area(), pi * R * R, deviation, disc_count_bound(R), check.mismatches);
  EXPECT_EQ(check.mismatches, 0);
  EXPECT_LE(std::abs(deviation), disc_count_bound(R));
}

TEST(Renderer, ColoursNoiseAndSupersampling) {
  const Ellipsoid seed(3.6, 1.8, 1.45);
  const View view = parallel_view(40, 320, 240, 640, 480);
  RenderOptions plain;
  const RenderedView a = render(seed, view, plain);
  // Background is exactly the background colour. The seed's centre faces the camera (n = -z in
  // camera coordinates) and the default light is (0, -1, -1) / sqrt(2), so it shows the albedo
  // times 0.35 + 0.65 / sqrt(2) = 0.81, rounded.
  EXPECT_EQ(a.image.at<cv::Vec3b>(5, 5), plain.background_bgr);
  const double lit = plain.ambient + (1 - plain.ambient) / std::sqrt(2.0);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(a.image.at<cv::Vec3b>(240, 320)[k], cvRound(plain.seed_bgr[k] * lit)) << "channel " << k;
  cv::Mat hsv;
  cv::cvtColor(a.image, hsv, cv::COLOR_BGR2HSV);
  const cv::Vec3b centre = hsv.at<cv::Vec3b>(240, 320);
  EXPECT_LE(centre[0], 30);  // wheat hue
  EXPECT_GE(centre[1], 60);

  RenderOptions fancy;
  fancy.supersampling = 4;
  fancy.blur_sigma_px = 1.0;
  fancy.noise_sigma = 5;
  fancy.noise_seed = 99;
  const RenderedView b = render(seed, view, fancy), c = render(seed, view, fancy);
  EXPECT_EQ(a.mask.pixels(), b.mask.pixels());               // the mask ignores the colour options
  EXPECT_EQ(cv::norm(b.image, c.image, cv::NORM_INF), 0.0);  // same seed, same image
  fancy.noise_seed = 100;
  EXPECT_GT(cv::norm(b.image, render(seed, view, fancy).image, cv::NORM_INF), 0.0);

  RenderOptions bad;
  bad.supersampling = 0;
  try {
    render(seed, view, bad);
    ADD_FAILURE() << "supersampling = 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("supersampling = 0"), std::string::npos);
  }
  View singular = view;
  singular.P.setZero();
  EXPECT_THROW(render(seed, singular), InputError);
}

}  // namespace
}  // namespace suite::carving
