#pragma once
// A table read from a CSV file: '#' comment lines, one header row, then rows of the same
// width; fields may be double-quoted (with "" for a quote inside). This is the format of the
// reference data in data/, of seed manifests and of results tables. Cells are
// kept as text; number() converts with an InputError that names the file, line and column.
// Not collective.
#include <filesystem>
#include <string>
#include <vector>

namespace suite::io {

class CsvTable {
 public:
  static CsvTable read(const std::filesystem::path& path);                    // InputError if unreadable
  static CsvTable parse(const std::string& text, const std::string& source);  // source: for messages

  const std::vector<std::string>& columns() const { return header_; }
  const std::vector<std::string>& comments() const { return comments_; }  // without the leading '#'
  std::size_t rows() const { return cells_.size(); }

  // Index of a column; InputError naming the columns there are (with a suggestion) if absent.
  std::size_t column(const std::string& name) const;
  const std::string& text(std::size_t row, const std::string& column) const;
  double number(std::size_t row, const std::string& column) const;
  std::vector<double> numbers(const std::string& column) const;
  // The first row whose `column` holds `value`; InputError listing the values there are if none.
  std::size_t find_row(const std::string& column, const std::string& value) const;

 private:
  std::string source_;
  std::vector<std::string> comments_, header_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<int> lines_;
};

// `text` as one CSV field that CsvTable reads back unchanged: quoted (with "" for a quote) when it
// holds a comma, a quote or blanks at its ends; line breaks become spaces (a record is one line).
std::string csv_field(std::string text);

}  // namespace suite::io
