#include "carving/measure/measure_seed.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "carving/image/segmentation.hpp"
#include "carving/io/voxel_output.hpp"
#include "carving/measure/hull_measurement.hpp"
#include "carving/render/renderer.hpp"
#include "carving/slicing/two_view.hpp"
#include "core/errors.hpp"
#include "core/run/run_record.hpp"

namespace suite::carving {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A second contour of at least this part of the seed's area in a view flags the seed
// `fragmented`: a broken seed, or another object, whose pieces the measurement leaves out.
constexpr double kFragmentShare = 0.1;

// The part of every view's silhouette the hull's image must cover; below it the views
// count as disagreeing with the calibration (measure/silhouette_agreement.hpp); the coverage that
// consistent and inconsistent view sets reach is measured in docs/carving.md, "Quality checks".
constexpr double kMinCoverage = 0.95;

// Wall time of a seed's phases, s (seed.json "times_s"; the batch benchmark's breakdown): measure
// is the carve with its quality checks and mesh, or the slices.
struct SeedTimes {
  double read = 0, segment = 0, measure = 0, outputs = 0;
};

struct SegmentedView {
  std::filesystem::path file;
  cv::Mat image;
  Segmentation segmentation;
  std::string frame_edge;  // the image edge the silhouette touches ("" for none)
};

// Every image read and segmented; the first image that cannot be read, has another size than
// the first, or shows no plausible seed fails the seed, naming the file.
std::vector<SegmentedView> segment_views(const std::vector<std::filesystem::path>& files,
                                         const SegmentationOptions& options, SeedTimes& times) {
  // Reserved: a view's masks would otherwise be copied at every growth (cv::Mat's move is not
  // noexcept, so the vector copies its elements), a fifth of a seed's time.
  std::vector<SegmentedView> views;
  views.reserve(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    auto t = std::chrono::steady_clock::now();
    SegmentedView v{files[i], read_image(files[i]), {}, ""};
    times.read += seconds_since(t);
    if (!views.empty() && v.image.size() != views[0].image.size())
      throw InputError(fmt::format(
          "image '{}' is {} x {} px but '{}' is {} x {} px; all views of a seed must have "
          "one size",
          files[i].string(), v.image.cols, v.image.rows, files[0].string(), views[0].image.cols, views[0].image.rows));
    t = std::chrono::steady_clock::now();
    v.segmentation = segment(v.image, options);
    times.segment += seconds_since(t);
    if (!v.segmentation.found)
      throw InputError(fmt::format("view {} ('{}'): {}", i + 1, files[i].filename().string(), v.segmentation.reason));
    const cv::Rect& b = v.segmentation.bounding_box;
    v.frame_edge = b.x == 0                         ? "left"
                   : b.y == 0                       ? "top"
                   : b.x + b.width == v.image.cols  ? "right"
                   : b.y + b.height == v.image.rows ? "bottom"
                                                    : "";
    views.push_back(std::move(v));
  }
  return views;
}

// The views side by side, contours in green (and `lines` per view in red), at most `columns`
// across, each cropped to the seed (the union of the contours' boxes and a margin) and scaled to
// at most `tile_width` px (reduced by a whole factor, each tile pixel the mean of a block of view
// pixels; or enlarged to `tile_width`): small enough to keep one per seed in a batch of thousands.
cv::Mat overlay_montage(const std::vector<SegmentedView>& views,
                        const std::vector<std::vector<OverlayLine>>& lines = {}, int columns = 6,
                        int tile_width = 200) {
  const int n = static_cast<int>(views.size());
  cv::Rect crop = views[0].segmentation.bounding_box;
  for (const auto& v : views) crop |= v.segmentation.bounding_box;
  const int margin = std::max(4, std::max(crop.width, crop.height) / 8);
  crop = cv::Rect(crop.x - margin, crop.y - margin, crop.width + 2 * margin, crop.height + 2 * margin) &
         cv::Rect(0, 0, views[0].image.cols, views[0].image.rows);
  // A whole reduction factor keeps cv::resize's block-mean path, a fifth of the cost of its
  // general area interpolation; the crop loses under `factor` px of margin to it.
  const int factor = std::max(1, (crop.width + tile_width - 1) / tile_width);
  if (factor > 1) {
    crop.width -= crop.width % factor, crop.height -= crop.height % factor;
    tile_width = crop.width / factor;
  }
  const int cols = std::min(columns, n), rows = (n + cols - 1) / cols;
  const double scale = static_cast<double>(tile_width) / crop.width;
  const int tile_height =
      factor > 1 ? crop.height / factor : std::max(1, static_cast<int>(std::round(crop.height * scale)));
  cv::Mat montage(rows * tile_height, cols * tile_width, CV_8UC3, cv::Scalar(0, 0, 0));
  // A frame pixel's position on its tile, in 1/16 px (pixel centres at integers on both).
  constexpr int kShift = 4;
  const auto on_tile = [&](const cv::Point2d& p) {
    return cv::Point(cvRound(((p.x - crop.x + 0.5) * scale - 0.5) * (1 << kShift)),
                     cvRound(((p.y - crop.y + 0.5) * scale - 0.5) * (1 << kShift)));
  };
  for (int i = 0; i < n; ++i) {
    // Each crop is scaled straight into its tile, and the contour drawn on the tile at the tile's
    // resolution (copying and drawing on the crops first was a tenth of a seed's time).
    cv::Mat tile = montage(cv::Rect((i % cols) * tile_width, (i / cols) * tile_height, tile_width, tile_height));
    cv::Mat view = views[i].image(crop);
    if (view.channels() == 1) cv::cvtColor(view, view, cv::COLOR_GRAY2BGR);
    cv::resize(view, tile, tile.size(), 0, 0, factor > 1 ? cv::INTER_AREA : cv::INTER_NEAREST);
    std::vector<cv::Point> contour;
    contour.reserve(views[i].segmentation.contour.size());
    for (const cv::Point& p : views[i].segmentation.contour) contour.push_back(on_tile(p));
    cv::polylines(tile, contour, true, cv::Scalar(0, 255, 0), 1, cv::LINE_8, kShift);
    if (i < static_cast<int>(lines.size()))
      for (const auto& l : lines[i])
        cv::line(tile, on_tile(l.from), on_tile(l.to), cv::Scalar(0, 0, 255), 1, cv::LINE_8, kShift);
  }
  return montage;
}

void measure_by_carving(const std::vector<SegmentedView>& segmented, const SeedProfile& profile,
                        const std::filesystem::path& dir, SeedRow& row, nlohmann::json& record, SeedTimes& times) {
  if (profile.camera.views && static_cast<int>(segmented.size()) != *profile.camera.views)
    throw InputError(
        fmt::format("{} images, but the profile's rig takes {} views (camera.views): a view is "
                    "missing or extra; give the seed every view of its turn",
                    segmented.size(), *profile.camera.views));
  std::vector<Mask> masks;
  for (const auto& v : segmented) masks.push_back(v.segmentation.mask);
  const auto start = std::chrono::steady_clock::now();
  std::optional<Registration> reg;
  const auto views = seed_views(profile.camera, profile.hull, masks, reg);
  if (reg)
    record["registration"] = {{"axis_column_px", reg->column},
                              {"origin_row_px", reg->axis.row},
                              {"axis_fit_residual_px", reg->axis.residual_px},
                              {"orbit_radius_px", reg->axis.orbit_radius_px},
                              {"calibrated_image_origin_px", {reg->placement.x0, reg->placement.y0}},
                              {"scale", reg->placement.scale},
                              {"turn", reg->placement.mirrored ? "reversed" : "same"},
                              {"search_volume_mm3", reg->volume_mm3},
                              {"other_turn_search_volume_mm3", reg->other_sense_volume_mm3}};
  const HullMeasurement hull = measure_hull(views, masks, profile.hull);
  times.measure = seconds_since(start);
  record["silhouette_coverage"] = hull.coverage;
  record["silhouette_check_s"] = hull.coverage_s;
  const auto worst =
      static_cast<std::size_t>(std::min_element(hull.coverage.begin(), hull.coverage.end()) - hull.coverage.begin());
  if (hull.coverage[worst] < kMinCoverage)
    throw InputError(fmt::format(
        "the silhouettes disagree with the calibration: the hull covers {:.1f}% of view {}'s silhouette ('{}'; "
        "at least {:.0f}% in every view when views and calibration agree); check that no view is missing and that "
        "the views' count and angles (camera.step) match the rig",
        100 * hull.coverage[worst], worst + 1, segmented[worst].file.filename().string(), 100 * kMinCoverage));
  row.length_mm = hull.length_mm, row.width_mm = hull.width_mm, row.thickness_mm = hull.thickness_mm;
  row.volume_mm3 = hull.volume_mm3;
  row.surface_mm2 = hull.surface_mm2;
  const auto outputs = std::chrono::steady_clock::now();
  write_png(dir / "overlays.png", overlay_montage(segmented));
  if (profile.hull.mesh) write_ply(dir / "surface.ply", hull.mesh);
  if (profile.hull.keep_occupancy) write_occupancy_h5(dir / "voxels.h5", hull.occupancy);
  times.outputs = seconds_since(outputs);
  record["carving"] = {{"voxels", hull.voxels},
                       {"voxel_mm", hull.grid.voxel.x()},
                       {"grid", hull.grid.n},
                       {"box_lo_mm", {hull.grid.lo.x(), hull.grid.lo.y(), hull.grid.lo.z()}},
                       {"cells_tested", hull.stats.cells},
                       {"view_tests", hull.stats.view_tests},
                       {"point_tests", hull.stats.point_tests},
                       {"mesh_triangles", hull.mesh.triangles.size()},
                       {"views_carve_and_mesh_s", times.measure}};
}

void measure_by_slicing(const std::vector<SegmentedView>& segmented, const SeedProfile& profile,
                        const std::filesystem::path& dir, SeedRow& row, nlohmann::json& record, SeedTimes& times) {
  if (segmented.size() != 2)
    throw InputError(
        fmt::format("the slicing method needs two images, the top view then the side view; this seed "
                    "has {}",
                    segmented.size()));
  const auto start = std::chrono::steady_clock::now();
  const TwoViewResult r =
      measure_two_view(segmented[0].segmentation.mask, segmented[1].segmentation.mask, profile.slicing);
  times.measure = seconds_since(start);
  row.length_mm = r.length_mm, row.width_mm = r.width_mm, row.thickness_mm = r.thickness_mm;
  row.volume_mm3 = r.volume_mm3;
  row.surface_mm2 = std::nan("");
  std::vector<std::vector<OverlayLine>> lines(2);
  for (const Slice& s : r.slices) {
    lines[0].push_back({{s.top_x_px, r.top_box.y0 - 0.5}, {s.top_x_px, r.top_box.y1 + 0.5}});
    lines[1].push_back({{s.side_x_px, r.side_box.y0 - 0.5}, {s.side_x_px, r.side_box.y1 + 0.5}});
  }
  const auto outputs = std::chrono::steady_clock::now();
  write_png(dir / "overlays.png", overlay_montage(segmented, lines, 2, 640));
  times.outputs = seconds_since(outputs);
  record["slicing"] = {{"slices", r.slices.size()},
                       {"scale_correction", r.scale},
                       {"neighbour_average", profile.slicing.neighbour_average},
                       {"px_per_mm_top", profile.slicing.px_per_mm_top},
                       {"px_per_mm_side", r.px_per_mm_side}};
}

}  // namespace

SeedRow measure_seed(const SeedEntry& seed, const SeedProfile& profile, const std::filesystem::path& dir) {
  const auto start = std::chrono::steady_clock::now();
  SeedRow row;
  row.id = seed.id;
  row.host = host_name();
  row.method = seed.method.empty() ? profile.method : seed.method;
  row.length_mm = row.width_mm = row.thickness_mm = row.volume_mm3 = std::nan("");
  row.surface_mm2 = row.density_mg_mm3 = std::nan("");
  try {
    if (row.method != profile.method)
      throw InputError(fmt::format("method '{}' but profile '{}' is for {}; name a {} profile for this seed",
                                   row.method, profile.source, profile.method, row.method));
    std::filesystem::create_directories(dir);
    const auto files = seed_image_files(seed);
    row.n_views = static_cast<int>(files.size());
    SeedTimes times;
    const auto segmented = segment_views(files, profile.segmentation, times);
    nlohmann::json record = {{"id", seed.id}, {"method", row.method}, {"profile", profile.source}};
    for (const auto& v : segmented) record["images"].push_back(v.file.string());
    // A silhouette on the image's edge may be cut off by the frame. On the left, right or top edge
    // that fails the seed; on the bottom edge it is flagged: a seed resting on the stage at the
    // frame's bottom is cut at the same plane in every view (the Kansas State photographs), and a
    // seed cut differently in some views fails the silhouette agreement below.
    std::vector<std::string> cut;
    for (std::size_t i = 0; i < segmented.size(); ++i) {
      const std::string& edge = segmented[i].frame_edge;
      if (edge.empty()) continue;
      record["frame_contact"].push_back({{"view", i + 1}, {"edge", edge}});
      if (edge != "bottom") cut.push_back(fmt::format("{} ({} edge)", i + 1, edge));
    }
    if (!cut.empty())
      throw InputError(
          fmt::format("the frame cuts the seed off in view{} {}: photograph it whole (a larger field "
                      "of view, or the seed further from the edges)",
                      cut.size() > 1 ? "s" : "", fmt::join(cut, ", ")));
    std::vector<std::string> flags;
    if (record.contains("frame_contact")) flags.emplace_back("touches_frame");
    for (std::size_t i = 0; i < segmented.size(); ++i) {
      const Segmentation& s = segmented[i].segmentation;
      if (s.other_area < kFragmentShare * s.area) continue;
      record["fragments"].push_back({{"view", i + 1}, {"seed_px", s.area}, {"other_px", s.other_area}});
    }
    if (record.contains("fragments")) flags.emplace_back("fragmented");
    row.quality = fmt::format("{}", fmt::join(flags, ";"));
    if (row.method == "carving") {
      measure_by_carving(segmented, profile, dir, row, record, times);
    } else {
      measure_by_slicing(segmented, profile, dir, row, record, times);
    }
    if (seed.weight_mg) row.density_mg_mm3 = density_mg_per_mm3(*seed.weight_mg, row.volume_mm3);
    record["length_mm"] = row.length_mm;
    record["width_mm"] = row.width_mm;
    record["thickness_mm"] = row.thickness_mm;
    record["volume_mm3"] = row.volume_mm3;
    if (std::isfinite(row.surface_mm2)) record["surface_mm2"] = row.surface_mm2;
    if (seed.weight_mg) record["weight_mg"] = *seed.weight_mg, record["density_mg_mm3"] = row.density_mg_mm3;
    record["times_s"] = {{"read_images", times.read},
                         {"segment", times.segment},
                         {"measure", times.measure},
                         {"write_outputs", times.outputs},
                         {"total", seconds_since(start)}};
    write_json_atomic(dir / "seed.json", record);
    row.ok = true;
  } catch (const std::exception& e) {  // a bad seed fails its row, never the batch
    row.ok = false;
    row.message = e.what();
  }
  row.wall_s = seconds_since(start);
  return row;
}

}  // namespace suite::carving
