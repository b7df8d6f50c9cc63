#include "benchmarks/carving/synthetic_seeds.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "carving/render/renderer.hpp"

namespace suite::carving::bench {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<View> parallel_rig(int views, double px_per_mm, int width, int height) {
  return ParallelTurntable{px_per_mm, width / 2.0, height / 2.0, views, 0.0, 2 * kPi / views, width, height}
      .all_views();
}

std::vector<View> pinhole_rig(int views, double focal_px, double distance_mm, int width, int height) {
  return Turntable{{focal_px, width / 2.0, height / 2.0}, distance_mm, views, 0.0, 2 * kPi / views, width, height}
      .all_views();
}

// The wheat rig of carving/examples/synthetic/wheat_ellipsoid.yaml: f = 6000 px, 100 mm, 640 x 480 px.
std::vector<View> wheat_rig(int views) {
  return pinhole_rig(views, 6000, 100, 640, 480);
}

// Renders every view's exact mask. One ray per pixel: the mask only uses the centre ray.
SyntheticSeed rendered(std::string name, std::string projection, std::shared_ptr<const Shape> shape,
                       std::vector<View> views, double cube_side_mm) {
  SyntheticSeed s{std::move(name), std::move(projection), std::move(shape), std::move(views), {}, cube_side_mm};
  RenderOptions options;
  options.supersampling = 1;
  for (const View& v : s.views) s.masks.push_back(render(*s.shape, v, options).mask);
  return s;
}

// Lying on the turntable like creased_grain.yaml: tilted about the long (x) axis, then turned
// about the turntable (y) axis.
Pose grain_pose(double tilt_rad, double turn_rad) {
  Pose pose;
  pose.rotation =
      rotation_matrix(Eigen::Vector3d::UnitY(), turn_rad) * rotation_matrix(Eigen::Vector3d::UnitX(), tilt_rad);
  return pose;
}

}  // namespace

SyntheticSeed parallel_sphere(int views, double px_per_mm) {
  const double radius = 2.0;
  const int size = static_cast<int>(std::ceil(2.5 * radius * px_per_mm));
  return rendered(fmt::format("sphere_parallel_r{:.0f}px", radius * px_per_mm), "parallel",
                  std::make_shared<Sphere>(radius), parallel_rig(views, px_per_mm, size, size), 2.5 * radius);
}

SyntheticSeed pinhole_sphere(int views, double focal_px) {
  const double radius = 2.0, distance = 50.0;
  const double image_radius_px = focal_px * std::tan(std::asin(radius / distance));  // the tangent cone's image
  const int size = static_cast<int>(std::ceil(2.5 * image_radius_px));
  return rendered(fmt::format("sphere_pinhole_r{:.0f}px", image_radius_px), "pinhole", std::make_shared<Sphere>(radius),
                  pinhole_rig(views, focal_px, distance, size, size), 2.5 * radius);
}

SyntheticSeed wheat_ellipsoid(int views) {
  auto shape = std::make_shared<Ellipsoid>(3.6, 1.45, 1.8, grain_pose(20 * kPi / 180, 0));
  return rendered("wheat_ellipsoid", "pinhole", std::move(shape), wheat_rig(views), 8.0);
}

SyntheticSeed creased_grain(int views, double crease_radius_mm, double crease_depth_mm, double turn_rad) {
  auto shape =
      std::make_shared<CreasedGrain>(3.6, 1.8, 1.45, crease_radius_mm, crease_depth_mm, grain_pose(kPi / 2, turn_rad));
  return rendered("creased_grain", "pinhole", std::move(shape), wheat_rig(views), 8.0);
}

SyntheticSeed uncreased_grain(int views, double turn_rad) {
  auto shape = std::make_shared<Ellipsoid>(3.6, 1.8, 1.45, grain_pose(kPi / 2, turn_rad));
  return rendered("uncreased_grain", "pinhole", std::move(shape), wheat_rig(views), 8.0);
}

SyntheticSeed every_nth_view(const SyntheticSeed& seed, int n) {
  const int all = static_cast<int>(seed.views.size());
  if (n < 1 || all % n != 0) throw std::invalid_argument("every_nth_view: the view count must divide " + seed.name);
  SyntheticSeed s{seed.name, seed.projection, seed.shape, {}, {}, seed.cube_side_mm};
  for (int i = 0; i < all; i += all / n) {
    s.views.push_back(seed.views[i]);
    s.masks.push_back(seed.masks[i]);
  }
  return s;
}

double analytic_sphere_hull_mm3(int views, double radius_mm) {
  const int sides = views % 2 == 0 ? views : 2 * views;
  return 4.0 * sides / 3.0 * std::tan(kPi / sides) * std::pow(radius_mm, 3);
}

}  // namespace suite::carving::bench
