#include "carving/measure/seed_profile.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"

namespace suite::carving {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<double> numbers(const config::Section& s, const std::string& key, std::vector<double> fallback,
                            std::size_t count, double lo, double hi) {
  const auto v = s.get<std::vector<double>>(key, fallback);
  if (v.size() != count) s.reject(key, fmt::format("give {} numbers", count));
  for (double x : v)
    if (!(x >= lo && x <= hi)) s.reject(key, fmt::format("each number must lie in [{}, {}]", lo, hi));
  return v;
}

}  // namespace

SegmentationOptions read_segmentation(const config::Section& s) {
  SegmentationOptions o;
  const auto low = numbers(s, "hsv_low", {0, 60, 0}, 3, 0, 255);
  const auto high = numbers(s, "hsv_high", {30, 255, 255}, 3, 0, 255);
  if (low[0] > 180 || high[0] > 180) s.reject("hsv_high", "hue runs from 0 to 180 in OpenCV's HSV");
  o.hsv_low = {static_cast<int>(low[0]), static_cast<int>(low[1]), static_cast<int>(low[2])};
  o.hsv_high = {static_cast<int>(high[0]), static_cast<int>(high[1]), static_cast<int>(high[2])};
  o.automatic = s.get<bool>("automatic", false);
  o.open_kernel_px = static_cast<int>(s.integer("open_px", o.open_kernel_px, 0, 99));
  o.close_kernel_px = static_cast<int>(s.integer("close_px", o.close_kernel_px, 0, 99));
  const auto area = numbers(s, "area_px", {o.min_area, o.max_area}, 2, 0, 1e12);
  if (area[0] > area[1]) s.reject("area_px", "give [smallest, largest] plausible contour area in px");
  o.min_area = area[0];
  o.max_area = area[1];
  return o;
}

CameraProfile read_camera_profile(const config::Section& s) {
  CameraProfile c;
  c.model = s.choice("model", {"turntable", "parallel", "projection_file"}, "turntable");
  if (c.model == "turntable") {
    c.K.focal_px = s.number("focal_px", config::Range::positive());
    const auto pp = numbers(s, "principal_point", {}, 2, -1e6, 1e6);
    c.K.cx = pp[0], c.K.cy = pp[1];
    c.distance_mm = s.quantity("distance", "mm", config::Range::positive());
  } else if (c.model == "parallel") {
    c.px_per_mm = s.number("px_per_mm", config::Range::positive());
    const auto pp = numbers(s, "principal_point", {}, 2, -1e6, 1e6);
    c.K.cx = pp[0], c.K.cy = pp[1];
  } else {
    c.projection_file = s.file("projection_file");
    c.projections = read_projection_file(c.projection_file, 0);
  }
  c.first_angle = s.quantity("first_angle", "rad", 0.0);  // projection files: used by frame_origin: auto
  if (s.has("step")) c.step = s.quantity("step", "rad", config::Range::positive());
  if (s.has("views")) c.views = static_cast<int>(s.integer("views", 36, 1, 10000));
  bool is_auto = false;
  if (s.has("frame_origin")) try {
      is_auto = s.get<std::string>("frame_origin") == "auto";
    } catch (const InputError&) {  // a list of two numbers
    }
  if (is_auto) {
    c.auto_frame_origin = true;
  } else {
    const auto o = numbers(s, "frame_origin", {0, 0}, 2, -1e6, 1e6);
    c.frame_origin = {o[0], o[1]};
  }
  c.frame_scale = s.number("frame_scale", 1.0, config::Range::positive());
  const auto turn = c.auto_frame_origin ? s.choice("frame_turn", {"same", "reversed", "auto"}, "auto")
                                        : s.choice("frame_turn", {"same", "reversed"}, "same");
  c.frame_turn = turn == "same" ? 1 : turn == "reversed" ? -1 : 0;
  return c;
}

SeedProfile read_seed_profile(const config::Config& cfg) {
  const auto root = cfg.root();
  SeedProfile p;
  p.source = cfg.source_name();
  p.method = root.choice("method", {"carving", "slicing"}, "carving");
  p.segmentation = read_segmentation(root.section_or_empty("segmentation"));
  if (p.method == "carving") {
    p.camera = read_camera_profile(root.section("camera"));
    const auto c = root.section_or_empty("carving");
    p.hull.resolution = static_cast<int>(c.integer("resolution", 256, 4, 4096));
    p.hull.subvoxel_samples = static_cast<int>(c.integer("subvoxel_samples", 0, 0, 16));
    p.hull.search_resolution = static_cast<int>(c.integer("search_resolution", 48, 8, 512));
    if (c.has("search_side")) p.hull.search_side_mm = c.quantity("search_side", "mm", config::Range::positive());
    p.hull.mesh = c.get<bool>("mesh", true);
    p.hull.mesh_resolution = static_cast<int>(c.integer("mesh_resolution", 128, 8, 1024));
    p.hull.keep_occupancy = c.get<bool>("voxels_h5", false);
    if (p.hull.keep_occupancy && !p.hull.mesh)
      c.reject("voxels_h5", "the voxel output is the mesh's grid; set mesh: true");
  } else {
    const auto s = root.section("slicing");
    p.slicing.slices = static_cast<int>(s.integer("slices", 50, 1, 100000));
    p.slicing.px_per_mm_top = s.number("px_per_mm", config::Range::positive());
    p.slicing.scale_correction = s.get<bool>("scale_correction", true);
    p.slicing.neighbour_average = s.get<bool>("neighbour_average", false);
  }
  cfg.finish();
  p.effective_yaml = cfg.effective_yaml();
  return p;
}

std::vector<View> profile_views(const CameraProfile& c, int images, int width, int height) {
  std::vector<View> views;
  if (c.model == "projection_file") {
    if (static_cast<int>(c.projections.size()) != images)
      throw InputError(
          fmt::format("projection file '{}' holds {} matrices but the seed has {} images; give one "
                      "matrix per image, in the images' order",
                      c.projection_file.string(), c.projections.size(), images));
    for (const auto& P : c.projections) views.push_back({P, width, height});
  } else {
    const double step = c.step.value_or(2 * std::numbers::pi / images);
    if (c.model == "turntable") {
      views = Turntable{c.K, c.distance_mm, images, c.first_angle, step, width, height}.all_views();
    } else {
      views = ParallelTurntable{c.px_per_mm, c.K.cx, c.K.cy, images, c.first_angle, step, width, height}.all_views();
    }
  }
  if (c.auto_frame_origin) return views;  // placed by seed_views()
  // The calibration belongs to images whose pixel (0, 0) is the photographs' frame_origin.
  return place_views(views, {c.frame_origin.x(), c.frame_origin.y(), c.frame_scale, c.frame_turn < 0}, width, height);
}

std::vector<double> profile_angles(const CameraProfile& c, int images) {
  const double step = c.step.value_or(2 * std::numbers::pi / images);
  std::vector<double> angles(static_cast<std::size_t>(images));
  for (int i = 0; i < images; ++i) angles[static_cast<std::size_t>(i)] = c.first_angle + step * i;
  return angles;
}

std::vector<View> seed_views(const CameraProfile& c, const HullOptions& hull, const std::vector<Mask>& masks,
                             std::optional<Registration>& registration) {
  registration.reset();
  if (masks.empty()) throw InputError("a seed needs at least one image");
  const int n = static_cast<int>(masks.size()), width = masks[0].width(), height = masks[0].height();
  std::vector<View> calibrated = profile_views(c, n, width, height);
  if (!c.auto_frame_origin) return calibrated;
  RegistrationOptions o;
  o.scale = c.frame_scale;
  o.orientation = c.frame_turn;
  if (o.orientation == 0) {  // the sense of rotation by hull volume on the search cube
    std::vector<View> scaled = calibrated;
    for (auto& v : scaled) v.P.topRows<2>() *= c.frame_scale;  // only the px/mm matters for the cube's size
    o.grid = search_cube(scaled, hull, 2 * hull.search_resolution);
  }
  registration = register_to_frames(masks, calibrated, profile_angles(c, n), o);
  return registration->views;
}

}  // namespace suite::carving
