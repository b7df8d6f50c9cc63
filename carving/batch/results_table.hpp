#pragma once
// A seed batch's results table (docs/methods/carving.md, "Batch"): one CSV row per seed, appended and
// flushed as each seed finishes, so a killed batch keeps every finished seed and a rerun skips
// them. Lengths in mm, volume in mm^3, surface in mm^2, density in mg/mm^3, wall time in s: the
// header says so. A failed seed has status "failed" and the reason in `message`; `quality` holds
// flags on a seed measured with a caveat (a table without the column, from before it, reads too).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/io/append_log.hpp"

namespace suite::carving {

struct SeedRow {
  std::string id, method;
  double length_mm = 0, width_mm = 0, thickness_mm = 0, volume_mm3 = 0;
  double surface_mm2 = 0, density_mg_mm3 = 0;  // NaN: not measured (written empty)
  int n_views = 0;
  bool ok = false;
  std::string quality;  // flags on a measured seed, ';'-separated (docs/carving.md, "Quality checks")
  std::string message;
  double wall_s = 0;
  std::string host;
};

// "id,method,length_mm,...": the columns, in order.
const std::vector<std::string>& results_columns();

// Appends rows to a results file (writes the header when the file is new or empty).
class ResultsWriter {
 public:
  explicit ResultsWriter(const std::filesystem::path& file);
  void append(const SeedRow& row);

 private:
  io::AppendLog log_;
};

// The rows of a results file (none if it does not exist); a torn last line is ignored.
std::vector<SeedRow> read_results(const std::filesystem::path& file);

// The rows of `ids` in that order, then any other rows (by id: a folder written before it had a
// register), so that no row is lost.
std::vector<SeedRow> in_order(const std::vector<std::string>& ids, std::map<std::string, SeedRow> rows);

// Writes `rows` as a complete results file (atomically).
void write_results(const std::filesystem::path& file, const std::vector<SeedRow>& rows);

}  // namespace suite::carving
