#pragma once
// A time series as CSV with units in the header: "time [s],discharge [m^3/s],...".
// Each row is written and flushed as it comes, so a killed run keeps every row so far.
// Not collective: create it on the one rank that writes (rank 0).
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace suite::io {

struct CsvColumn {
  std::string name;
  std::string unit;  // "" for dimensionless
};

class CsvSeries {
 public:
  // Creates (truncates) the file and writes the header.
  CsvSeries(std::filesystem::path path, std::vector<CsvColumn> columns);
  // Restart: keeps the rows of an existing file whose first column is <= t and appends after
  // them. Throws InputError if the existing header has other columns.
  static CsvSeries resume_at(std::filesystem::path path, std::vector<CsvColumn> columns, double t);

  void append(std::span<const double> row);
  void append(std::initializer_list<double> row) { append(std::span<const double>(row.begin(), row.size())); }
  std::string header() const;
  const std::filesystem::path& path() const { return path_; }

 private:
  CsvSeries(std::filesystem::path path, std::vector<CsvColumn> columns, bool truncate);
  std::filesystem::path path_;
  std::vector<CsvColumn> columns_;
  std::ofstream out_;
};

}  // namespace suite::io
