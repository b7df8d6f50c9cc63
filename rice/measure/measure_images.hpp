#pragma once
// Measures a list of photographs into one results table (docs/rice.md, "Outputs"): one row per
// grain, and for an image that cannot be measured (missing, unreadable, empty, no grain found) one
// row with status "failed" and the reason; the other images are measured all the same. Not
// collective.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/log/logger.hpp"
#include "rice/measure/grain_traits.hpp"

namespace suite::rice {

struct ResultRow {
  std::string image;    // the file as given
  GrainTraits traits;   // grain 0 for a failed image
  std::string status;   // ok, flagged or failed
  std::string message;  // failed: why, and what to do
  DishLevels levels;

  // The row of an image that could not be measured.
  static ResultRow failed(std::string image, std::string message) {
    ResultRow r;
    r.image = std::move(image);
    r.status = "failed";
    r.message = std::move(message);
    return r;
  }
};

// The table's columns, in order (units in the names and in the '#' line above them).
const std::vector<std::string>& result_columns();

// Measures every image (folders are expanded, image_files.hpp) and writes DIR/results.csv and
// DIR/measure.json; with `overlays` also DIR/overlays/<image>.png (kernels red, gel green, flagged
// grains yellow, each grain's number). Returns the rows in image order.
std::vector<ResultRow> measure_images(const std::vector<std::filesystem::path>& targets, const MeasureOptions& options,
                                      const std::filesystem::path& out, bool overlays, Logger& log);

// Writes `rows` as a complete results table (atomically).
void write_results(const std::filesystem::path& file, const std::vector<ResultRow>& rows, double mm_per_px);

}  // namespace suite::rice
