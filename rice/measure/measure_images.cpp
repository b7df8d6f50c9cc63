#include "rice/measure/measure_images.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "rice/measure/image_files.hpp"

namespace suite::rice {
namespace {

std::string number(double x, const char* format = "{:.6g}") {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : "";
}

void write_overlay(const std::filesystem::path& path, const cv::Mat& grey, const ImageTraits& t) {
  cv::Mat overlay;
  cv::cvtColor(grey, overlay, cv::COLOR_GRAY2BGR);
  auto outline = [&](const cv::Mat& mask, const cv::Scalar& colour) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
    cv::drawContours(overlay, contours, -1, colour, 1);
  };
  outline(t.gel, {0, 200, 0});
  outline(t.kernel, {0, 0, 255});
  for (const auto& g : t.grains) {
    const cv::Point at(static_cast<int>(g.x_px), static_cast<int>(g.y_px));
    cv::putText(overlay, std::to_string(g.grain), at, cv::FONT_HERSHEY_SIMPLEX, 1.5,
                g.ok ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 255, 255), 3);
  }
  write_png(path, overlay);
}

}  // namespace

const std::vector<std::string>& result_columns() {
  static const std::vector<std::string> columns = {"image",
                                                   "grain",
                                                   "x_px",
                                                   "y_px",
                                                   "status",
                                                   "quality",
                                                   "kernel_area_mm2",
                                                   "kernel_pieces",
                                                   "kernel_solidity",
                                                   "kernel_length_mm",
                                                   "kernel_width_mm",
                                                   "gel_area_mm2",
                                                   "gel_kernel_ratio",
                                                   "collar_completeness",
                                                   "kernel_share",
                                                   "grain_area_mm2",
                                                   "dish_level",
                                                   "grain_threshold",
                                                   "kernel_threshold",
                                                   "message"};
  return columns;
}

void write_results(const std::filesystem::path& file, const std::vector<ResultRow>& rows, double mm_per_px) {
  std::string text = fmt::format(
      "# riceasv measure, pixel size {} mm: positions in pixels, lengths in mm, areas in mm^2; solidity, ratio, "
      "completeness and share are fractions (empty: undefined, e.g. no kernel); levels in grey levels 0..255\n{}\n",
      mm_per_px, fmt::join(result_columns(), ","));
  for (const auto& r : rows) {
    const GrainTraits& g = r.traits;
    if (r.status == "failed") {
      text += fmt::format("{},0,,,failed,,,,,,,,,,,,,,,{}\n", io::csv_field(r.image), io::csv_field(r.message));
      continue;
    }
    text += fmt::format(
        "{},{},{:.1f},{:.1f},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", io::csv_field(r.image), g.grain,
        g.x_px, g.y_px, r.status, g.quality, number(g.kernel_area_mm2), g.kernel_pieces,
        number(g.kernel_solidity, "{:.4f}"), number(g.kernel_length_mm, "{:.4f}"), number(g.kernel_width_mm, "{:.4f}"),
        number(g.gel_area_mm2), number(g.gel_kernel_ratio), number(g.collar_completeness, "{:.4f}"),
        number(g.kernel_share, "{:.4f}"), number(g.grain_area_mm2), number(r.levels.dish, "{:.1f}"),
        number(r.levels.grain_threshold, "{:.1f}"),
        r.levels.kernel_threshold < 256 ? number(r.levels.kernel_threshold, "{:.1f}") : "", io::csv_field(r.message));
  }
  io::write_file_atomic(file, text);
}

std::vector<ResultRow> measure_images(const std::vector<std::filesystem::path>& targets, const MeasureOptions& options,
                                      const std::filesystem::path& out, bool overlays, Logger& log) {
  const auto images = expand_image_arguments(targets);
  std::error_code ec;
  std::filesystem::create_directories(overlays ? out / "overlays" : out, ec);
  if (ec)
    throw InputError(fmt::format("cannot create the output folder '{}': {}; choose a folder you can write",
                                 out.string(), ec.message()));
  std::vector<ResultRow> rows;
  nlohmann::json record = {{"program", "riceasv measure"}, {"pixel_size_mm", options.mm_per_px}};
  for (const auto& path : images) {
    const std::string name = path.string();
    try {
      const cv::Mat grey = read_grey(path);
      const ImageTraits t = measure_grains(grey, options);
      if (t.grains.empty())
        throw InputError(
            fmt::format("no grain found in '{}' (dish level {:.0f}, populations: {}); check that the "
                        "grains lie on a dark dish and that --pixel-size is right",
                        name, t.levels.dish, t.levels.populations));
      int flagged = 0;
      for (const auto& g : t.grains) {
        rows.push_back({name, g, g.ok ? "ok" : "flagged", "", t.levels});
        flagged += !g.ok;
      }
      record["images"].push_back({{"image", name},
                                  {"grains", t.grains.size()},
                                  {"flagged", flagged},
                                  {"populations", t.levels.populations},
                                  {"dish_level", t.levels.dish},
                                  {"noise", t.levels.noise},
                                  {"gel_level", t.levels.gel},
                                  {"kernel_level", t.levels.kernel},
                                  {"contrast", t.levels.contrast},
                                  {"separation", t.levels.separation}});
      if (overlays) write_overlay(out / "overlays" / (path.stem().string() + ".png"), grey, t);
      log.info("{}: {} grains ({} flagged), {}", name, t.grains.size(), flagged, t.levels.populations);
    } catch (const InputError& e) {
      rows.push_back(ResultRow::failed(name, e.what()));
      record["images"].push_back({{"image", name}, {"failed", e.what()}});
    } catch (const cv::Exception& e) {
      const std::string message = fmt::format("OpenCV failed on '{}': {}; check that it is a photograph", name, e.err);
      rows.push_back(ResultRow::failed(name, message));
      record["images"].push_back({{"image", name}, {"failed", message}});
    }
  }
  write_results(out / "results.csv", rows, options.mm_per_px);
  io::write_file_atomic(out / "measure.json", record.dump(2) + "\n");
  return rows;
}

}  // namespace suite::rice
