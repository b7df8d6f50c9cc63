#include "carving/app/calibrate_command.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "carving/batch/manifest.hpp"
#include "carving/calibration/ball.hpp"
#include "carving/calibration/chessboard.hpp"
#include "carving/calibration/turntable_axis.hpp"
#include "carving/image/segmentation.hpp"
#include "carving/measure/seed_profile.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/run/run_record.hpp"

namespace suite::carving {
namespace {

std::vector<std::filesystem::path> image_files(const CalibrateRequest& r) {
  if (r.images.empty())
    throw InputError(fmt::format("seedcarve calibrate {} needs images (files, or a folder of them)", r.target));
  SeedEntry all;
  all.id = "calibration";
  for (const auto& i : r.images) all.images.emplace_back(i);
  return seed_image_files(all);
}

// The profile's segmentation, or Otsu's threshold on hue with any area when there is no profile.
SegmentationOptions segmentation_of(const CalibrateRequest& r) {
  if (r.profile.empty()) {
    SegmentationOptions o;
    o.automatic = true;
    o.min_area = 50;
    o.max_area = 1e12;
    return o;
  }
  return read_segmentation(config::Config::from_file(r.profile, r.overrides).root().section_or_empty("segmentation"));
}

double required(const std::optional<double>& value, const char* flag, const std::string& target) {
  if (!value || !(*value > 0))
    throw InputError(fmt::format("seedcarve calibrate {} needs {} with a positive number", target, flag));
  return *value;
}

Segmentation segmented(const std::filesystem::path& file, const SegmentationOptions& options) {
  Segmentation s = segment_file(file, options);
  if (!s.found) throw InputError(fmt::format("image '{}': {}", file.string(), s.reason));
  return s;
}

void ball(const CalibrateRequest& r, nlohmann::json& out, std::string& yaml, Logger& log) {
  const double diameter = required(r.diameter_mm, "--diameter MM (the ball's diameter)", r.target);
  const double focal = r.focal_px ? required(r.focal_px, "--focal PX", r.target) : std::nan("");
  const auto options = segmentation_of(r);
  double px_per_mm = 0, distance = 0;
  const auto files = image_files(r);
  for (const auto& file : files) {
    const BallCalibration b = calibrate_ball(segmented(file, options).mask, diameter, focal);
    out["images"].push_back({{"image", file.string()},
                             {"px_per_mm", b.px_per_mm},
                             {"radius_px", b.radius_px},
                             {"centre_px", {b.centre_x, b.centre_y}},
                             {"distance_mm", std::isfinite(b.distance_mm) ? nlohmann::json(b.distance_mm) : nullptr},
                             {"fit_rms_px", b.fit_rms_px},
                             {"outline_points", b.outline_points}});
    log.info("{}: radius {:.3f} px (fit rms {:.3f} px), {:.4f} px/mm{}", file.filename().string(), b.radius_px,
             b.fit_rms_px, b.px_per_mm, std::isfinite(b.distance_mm) ? fmt::format(", distance {:.4f} mm", b.distance_mm) : "");
    px_per_mm += b.px_per_mm / static_cast<double>(files.size());
    distance += b.distance_mm / static_cast<double>(files.size());
  }
  out["px_per_mm"] = px_per_mm;
  yaml += fmt::format("px_per_mm: {:.6g}      # parallel model, or slicing.px_per_mm\n", px_per_mm);
  if (std::isfinite(focal)) {
    out["distance_mm"] = distance;
    yaml += fmt::format("distance: {:.6g} mm   # turntable model, with focal_px: {:.6g}\n", distance, focal);
  }
}

cv::Size corner_grid(const std::string& text) {
  int c = 0, rows = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &c, &x, &rows) != 3 || (x != 'x' && x != 'X') || c < 2 || rows < 2)
    throw InputError(fmt::format("--corners '{}': give the board's inner corners as COLUMNSxROWS, e.g. 9x6", text));
  return {c, rows};
}

void chessboard(const CalibrateRequest& r, nlohmann::json& out, std::string& yaml, Logger& log) {
  if (r.corners.empty()) throw InputError("seedcarve calibrate chessboard needs --corners CxR (inner corners, e.g. 9x6)");
  const cv::Size inner = corner_grid(r.corners);
  const double square = required(r.square_mm, "--square MM (the side of one square)", r.target);
  std::vector<cv::Mat> images;
  const auto files = image_files(r);
  for (const auto& f : files) images.push_back(read_image(f));
  const ChessboardCalibration c = calibrate_chessboard(images, inner, square);
  out["focal_px"] = c.intrinsics.focal_px;
  out["fx_px"] = c.fx, out["fy_px"] = c.fy;
  out["principal_point_px"] = {c.intrinsics.cx, c.intrinsics.cy};
  out["distortion_k1_k2_p1_p2_k3"] = c.distortion;
  out["rms_px"] = c.rms_px;
  for (std::size_t i = 0; i < files.size(); ++i)
    out["images"].push_back({{"image", files[i].string()}, {"rms_px", c.per_image_rms_px.at(i)}});
  log.info("{} boards: focal {:.2f} px (fx {:.2f}, fy {:.2f}), principal point ({:.2f}, {:.2f}), rms {:.3f} px",
           c.images, c.intrinsics.focal_px, c.fx, c.fy, c.intrinsics.cx, c.intrinsics.cy, c.rms_px);
  yaml += fmt::format("focal_px: {:.6g}\nprincipal_point: [{:.6g}, {:.6g}]\n", c.intrinsics.focal_px, c.intrinsics.cx,
                      c.intrinsics.cy);
}

void axis(const CalibrateRequest& r, nlohmann::json& out, std::string& yaml, Logger& log) {
  if (r.profile.empty())
    throw InputError("seedcarve calibrate axis needs --profile PROFILE.yaml (its segmentation and turntable angles)");
  const auto cfg = config::Config::from_file(r.profile, r.overrides);
  const auto options = read_segmentation(cfg.root().section_or_empty("segmentation"));
  const auto camera = read_camera_profile(cfg.root().section("camera"));
  std::vector<Mask> masks;
  const auto files = image_files(r);
  for (const auto& f : files) masks.push_back(segmented(f, options).mask);
  const AxisEstimate a = estimate_axis(masks, profile_angles(camera, static_cast<int>(masks.size())));
  out["axis_column_px"] = a.column;
  out["axis_column_stderr_px"] = a.column_stderr_px;
  out["origin_row_px"] = a.row;
  out["base_row_px"] = a.base_row;
  out["fit_residual_px"] = a.residual_px;
  out["orbit_radius_px"] = a.orbit_radius_px;
  out["views"] = masks.size();
  log.info("{} views: turntable axis at column {:.3f} +- {:.3f} px (fit rms {:.3f} px), seed centre row {:.2f}, "
           "base row {:.1f}; the seed swings {:.1f} px about the axis",
           masks.size(), a.column, a.column_stderr_px, a.residual_px, a.row, a.base_row, a.orbit_radius_px);
  yaml += fmt::format("# axis column {:.4f} px, origin row {:.4f} px in the photographs; with a calibration for\n"
                      "# the photographs themselves: principal_point: [{:.4f}, {:.4f}]\n",
                      a.column, a.row, a.column, a.row);
}

}  // namespace

void run_calibrate(const CalibrateRequest& r, Logger& log) {
  nlohmann::json out = {{"calibration", r.target}};
  std::string yaml = fmt::format("# seedcarve calibrate {}: lines for the camera: section of a profile\n", r.target);
  if (r.target == "ball") {
    ball(r, out, yaml, log);
  } else if (r.target == "chessboard") {
    chessboard(r, out, yaml, log);
  } else if (r.target == "axis") {
    axis(r, out, yaml, log);
  } else {
    throw InputError(fmt::format("seedcarve calibrate '{}': give ball, chessboard or axis", r.target));
  }
  std::filesystem::create_directories(r.out);
  write_json_atomic(r.out / "calibration.json", out);
  io::write_file_atomic(r.out / "camera.yaml", yaml);
  log.info("wrote {} and {}", (r.out / "calibration.json").string(), (r.out / "camera.yaml").string());
}

}  // namespace suite::carving
