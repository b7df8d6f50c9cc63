#include "carving/render/render_scene.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "carving/measure/seed_profile.hpp"
#include "carving/render/renderer.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/run/run_record.hpp"

namespace suite::carving {
namespace {

std::vector<double> fixed_list(const config::Section& s, const std::string& key, std::size_t count,
                               std::vector<double> fallback = {}) {
  const auto v = fallback.empty() ? s.get<std::vector<double>>(key) : s.get<std::vector<double>>(key, fallback);
  if (v.size() != count) s.reject(key, fmt::format("give {} numbers", count));
  for (double x : v)
    if (!std::isfinite(x)) s.reject(key, "give finite numbers");
  return v;
}

Eigen::Vector3d positive_vector(const config::Section& s, const std::string& key) {
  const auto v = fixed_list(s, key, 3);
  for (double x : v)
    if (!(x > 0)) s.reject(key, "give three lengths > 0 in mm");
  return {v[0], v[1], v[2]};
}

// The top and side cameras of a two-view rig: the top one looks down the turntable (y) axis, the
// side one horizontally; in both the seed's long (x) axis runs along the image rows.
std::vector<View> two_view_rig(const CameraProfile& c, int width, int height) {
  const Eigen::Matrix3d top = rotation_matrix(Eigen::Vector3d::UnitX(), std::numbers::pi / 2);
  const Eigen::Matrix3d side = Eigen::Matrix3d::Identity();
  if (c.model == "turntable") {
    const Eigen::Vector3d t(0, 0, c.distance_mm);
    return {{pinhole_projection(c.K, top, t), width, height}, {pinhole_projection(c.K, side, t), width, height}};
  }
  return {{parallel_projection(c.px_per_mm, c.K.cx, c.K.cy, top), width, height},
          {parallel_projection(c.px_per_mm, c.K.cx, c.K.cy, side), width, height}};
}

}  // namespace

std::unique_ptr<Shape> read_shape(const config::Section& s) {
  const std::string type = s.choice("type", {"sphere", "ellipsoid", "superellipsoid", "creased_grain"});
  Pose pose;
  const double tilt = s.quantity("tilt", "rad", 0.0), turn = s.quantity("turn", "rad", 0.0);
  pose.rotation = rotation_matrix(Eigen::Vector3d::UnitY(), turn) * rotation_matrix(Eigen::Vector3d::UnitX(), tilt);
  const auto c = fixed_list(s, "centre", 3, {0, 0, 0});
  pose.centre = {c[0], c[1], c[2]};
  if (type == "sphere") return std::make_unique<Sphere>(s.quantity("radius", "mm", config::Range::positive()), pose);
  const Eigen::Vector3d a = positive_vector(s, "semi_axes");
  if (type == "ellipsoid") return std::make_unique<Ellipsoid>(a.x(), a.y(), a.z(), pose);
  if (type == "superellipsoid") {
    const auto e = fixed_list(s, "exponents", 2);
    for (double x : e)
      if (!(x >= 0.1 && x <= 4)) s.reject("exponents", "each exponent must lie in [0.1, 4]");
    return std::make_unique<Superellipsoid>(a.x(), a.y(), a.z(), e[0], e[1], pose);
  }
  const auto crease = fixed_list(s, "crease", 2);
  if (!(crease[0] > 0 && crease[1] > 0 && crease[1] < a.z()))
    s.reject("crease",
             fmt::format("give [radius, depth] in mm, both > 0 and the depth below the half thickness {}", a.z()));
  return std::make_unique<CreasedGrain>(a.x(), a.y(), a.z(), crease[0], crease[1], pose);
}

RenderSummary render_scene(const config::Config& scene, const std::filesystem::path& out) {
  const auto root = scene.root();
  const auto shape = read_shape(root.section("shape"));
  const std::string method = root.choice("method", {"carving", "slicing"}, "carving");
  const auto camera_section = root.section("camera");
  const CameraProfile camera = read_camera_profile(camera_section);
  if (camera.model == "projection_file" || camera.auto_frame_origin)
    camera_section.reject("model", "render needs a turntable or parallel camera with a fixed frame_origin");
  const int views = method == "slicing" ? 2 : static_cast<int>(root.integer("views", 36, 1, 3600));
  const auto size = fixed_list(root, "image", 2, {640, 480});
  const int width = static_cast<int>(size[0]), height = static_cast<int>(size[1]);
  if (width < 8 || height < 8 || width > 20000 || height > 20000)
    root.reject("image", "give [width, height] in px, each 8 to 20000");
  const auto r = root.section_or_empty("render");
  RenderOptions options;
  options.supersampling = static_cast<int>(r.integer("supersampling", 2, 1, 16));
  options.blur_sigma_px = r.number("blur_px", 0.0, config::Range::between(0, 50));
  options.noise_sigma = r.number("noise", 0.0, config::Range::between(0, 100));
  options.noise_seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 1LL << 62));
  scene.finish();

  std::filesystem::create_directories(out / "masks");
  const auto cameras =
      method == "slicing" ? two_view_rig(camera, width, height) : profile_views(camera, views, width, height);
  long long smallest = -1, largest = 0;
  for (int v = 0; v < views; ++v) {
    RenderOptions o = options;
    o.noise_seed = options.noise_seed + static_cast<std::uint64_t>(v);
    const RenderedView image = render(*shape, cameras[v], o);
    const std::string name = method == "slicing" ? (v == 0 ? "top" : "side") : fmt::format("view_{:02d}", v + 1);
    write_png(out / (name + ".png"), image.image);
    write_mask_png(out / "masks" / (name + ".png"), image.mask);
    smallest = smallest < 0 ? image.mask.area() : std::min(smallest, image.mask.area());
    largest = std::max(largest, image.mask.area());
  }
  // A profile that measures these images with the calibration they were rendered with.
  std::string profile = fmt::format(
      "# Measures the images `seedcarve render` wrote beside this file, with their own calibration.\n"
      "method: {}\nsegmentation:\n  area_px: [{}, {}]\n",
      method, smallest / 2, largest * 2);
  if (method == "carving") {
    profile += "camera:\n" + fmt::format("  model: {}\n", camera.model);
    if (camera.model == "turntable")
      profile += fmt::format("  focal_px: {:.10g}\n  distance: {:.10g} mm\n", camera.K.focal_px, camera.distance_mm);
    else
      profile += fmt::format("  px_per_mm: {:.10g}\n", camera.px_per_mm);
    profile += fmt::format("  principal_point: [{:.10g}, {:.10g}]\n  first_angle: {:.12g} deg\n", camera.K.cx,
                           camera.K.cy, camera.first_angle * 180 / std::numbers::pi);
    if (camera.step) profile += fmt::format("  step: {:.12g} deg\n", *camera.step * 180 / std::numbers::pi);
    profile += fmt::format("  views: {}\n", views);
    profile += fmt::format("  frame_origin: [{:.10g}, {:.10g}]\n", camera.frame_origin.x(), camera.frame_origin.y());
  } else {
    const double px_per_mm = camera.model == "parallel" ? camera.px_per_mm : camera.K.focal_px / camera.distance_mm;
    profile += fmt::format("slicing:\n  px_per_mm: {:.10g}\n", px_per_mm);
  }
  io::write_file_atomic(out / "profile.yaml", profile);
  write_json_atomic(out / "truth.json",
                    {{"shape", shape->name()}, {"volume_mm3", shape->volume()}, {"views", views}, {"method", method}});
  scene.write_effective(out / "effective_config.yaml");
  return {shape->name(), shape->volume(), views};
}

}  // namespace suite::carving
