#include "core/io/csv_series.hpp"

#include <fmt/format.h>

#include <charconv>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::io {

CsvSeries::CsvSeries(std::filesystem::path path, std::vector<CsvColumn> columns)
    : CsvSeries(std::move(path), std::move(columns), true) {}

CsvSeries::CsvSeries(std::filesystem::path path, std::vector<CsvColumn> columns, bool truncate)
    : path_(std::move(path)), columns_(std::move(columns)) {
  out_.open(path_, truncate ? std::ios::trunc : std::ios::app);
  if (!out_)
    throw InputError(
        fmt::format("cannot write CSV file '{}'; check that its folder exists and is writable", path_.string()));
  if (truncate) {
    out_ << header() << '\n';
    out_.flush();
  }
}

namespace {
std::string header_of(const std::vector<CsvColumn>& columns) {
  std::string h;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i) h += ',';
    h += columns[i].name;
    if (!columns[i].unit.empty()) h += " [" + columns[i].unit + "]";
  }
  return h;
}
// 12 significant digits: readable, and far below the precision of any measured quantity.
std::string format_value(double v) {
  return fmt::format("{:.12g}", v);
}
}  // namespace

std::string CsvSeries::header() const {
  return header_of(columns_);
}

CsvSeries CsvSeries::resume_at(std::filesystem::path path, std::vector<CsvColumn> columns, double t) {
  std::ifstream in(path);
  if (!in) return CsvSeries(std::move(path), std::move(columns), true);
  std::string line, kept;
  std::getline(in, line);
  const std::string expected = header_of(columns);
  // Rows hold times as append() printed them; compare against t printed the same way, so the
  // row written at t itself is kept whichever way its last digit was rounded.
  double t_as_written = 0;
  const std::string t_text = format_value(t);
  std::from_chars(t_text.data(), t_text.data() + t_text.size(), t_as_written);
  if (line != expected) {
    throw InputError(
        fmt::format("cannot resume '{}': its header '{}' differs from '{}'; it belongs to another "
                    "run, move it away or start without restart",
                    path.string(), line, expected));
  }
  kept = line + '\n';
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    double time = 0;
    const auto end = line.find(',');
    const char* last = line.data() + (end == std::string::npos ? line.size() : end);
    if (std::from_chars(line.data(), last, time).ptr != last)
      throw InputError(
          fmt::format("cannot resume '{}': line {} does not start with a time ('{}')", path.string(), number, line));
    if (time <= t_as_written) kept += line + '\n';
  }
  in.close();
  write_file_atomic(path, kept);
  return CsvSeries(std::move(path), std::move(columns), false);
}

void CsvSeries::append(std::span<const double> row) {
  if (row.size() != columns_.size())
    throw LibraryError(
        fmt::format("CSV '{}': a row of {} values for {} columns", path_.string(), row.size(), columns_.size()));
  std::string s;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i) s += ',';
    s += format_value(row[i]);
  }
  out_ << s << '\n';
  out_.flush();
  if (!out_) throw LibraryError(fmt::format("writing a row to '{}' failed (disk full?)", path_.string()));
}

}  // namespace suite::io
