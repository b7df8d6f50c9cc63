#include "carving/batch/results_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"

namespace suite::carving {
namespace {

constexpr const char* kUnits =
    "# seedcarve results: lengths in mm, volume in mm^3, surface in mm^2, density in mg/mm^3, wall time in s";

std::string number(double x) {
  return std::isfinite(x) ? fmt::format("{:.6g}", x) : "";
}

std::string format_row(const SeedRow& r) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{:.3f},{}", io::csv_field(r.id), r.method,
                     number(r.length_mm), number(r.width_mm), number(r.thickness_mm), number(r.volume_mm3),
                     number(r.surface_mm2), number(r.density_mg_mm3), r.n_views, r.ok ? "ok" : "failed",
                     io::csv_field(r.quality), io::csv_field(r.message), r.wall_s, io::csv_field(r.host));
}

std::string header() {
  return std::string(kUnits) + "\n" + fmt::format("{}", fmt::join(results_columns(), ","));
}

}  // namespace

const std::vector<std::string>& results_columns() {
  static const std::vector<std::string> columns = {
      "id",      "method", "length_mm", "width_mm", "thickness_mm", "volume_mm3", "surface_mm2", "density_mg_mm3",
      "n_views", "status", "quality",   "message",  "wall_s",       "host"};
  return columns;
}

namespace {

// The columns before `quality` was added.
bool legacy_columns(const std::vector<std::string>& columns) {
  std::vector<std::string> legacy = results_columns();
  legacy.erase(std::find(legacy.begin(), legacy.end(), "quality"));
  return columns == legacy;
}

}  // namespace

ResultsWriter::ResultsWriter(const std::filesystem::path& file) : log_(file, "seed results table") {
  std::error_code ec;
  if (std::filesystem::file_size(file, ec) == 0) log_.append(header());
}

void ResultsWriter::append(const SeedRow& row) {
  log_.append(format_row(row));
}

std::vector<SeedRow> read_results(const std::filesystem::path& file) {
  std::vector<SeedRow> rows;
  if (!std::filesystem::exists(file)) return rows;
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.resize(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);  // a torn last line is not a row
  if (text.empty()) return rows;
  const io::CsvTable t = io::CsvTable::parse(text, file.string());
  const bool legacy = legacy_columns(t.columns());
  if (t.columns() != results_columns() && !legacy)
    throw InputError(
        fmt::format("'{}' is not a seedcarve results table (its columns are {}); move it away or "
                    "choose another output folder",
                    file.string(), fmt::join(t.columns(), ",")));
  auto value = [&](std::size_t r, const char* c) { return t.text(r, c).empty() ? std::nan("") : t.number(r, c); };
  for (std::size_t r = 0; r < t.rows(); ++r) {
    SeedRow s;
    s.id = t.text(r, "id");
    s.method = t.text(r, "method");
    s.length_mm = value(r, "length_mm");
    s.width_mm = value(r, "width_mm");
    s.thickness_mm = value(r, "thickness_mm");
    s.volume_mm3 = value(r, "volume_mm3");
    s.surface_mm2 = value(r, "surface_mm2");
    s.density_mg_mm3 = value(r, "density_mg_mm3");
    s.n_views = static_cast<int>(t.number(r, "n_views"));
    s.ok = t.text(r, "status") == "ok";
    if (!legacy) s.quality = t.text(r, "quality");
    s.message = t.text(r, "message");
    s.wall_s = t.number(r, "wall_s");
    s.host = t.text(r, "host");
    rows.push_back(std::move(s));
  }
  return rows;
}

void write_results(const std::filesystem::path& file, const std::vector<SeedRow>& rows) {
  std::string text = header() + "\n";
  for (const auto& r : rows) text += format_row(r) + "\n";
  io::write_file_atomic(file, text);
}

std::vector<SeedRow> in_order(const std::vector<std::string>& ids, std::map<std::string, SeedRow> rows) {
  std::vector<SeedRow> out;
  for (const auto& id : ids)
    if (auto it = rows.find(id); it != rows.end()) {
      out.push_back(std::move(it->second));
      rows.erase(it);
    }
  for (auto& [id, row] : rows) out.push_back(std::move(row));
  return out;
}

}  // namespace suite::carving
