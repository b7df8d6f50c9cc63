#include "core/io/csv_table.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/config/suggest.hpp"
#include "core/errors.hpp"

namespace suite::io {

namespace {

std::string trimmed(const std::string& f) {
  const auto a = f.find_first_not_of(" \t"), b = f.find_last_not_of(" \t");
  return a == std::string::npos ? "" : f.substr(a, b - a + 1);
}

// Splits one CSV record: fields separated by commas; a field may be double-quoted, with ""
// for a quote inside; blanks around unquoted fields are not data. False on an open quote.
bool split_record(const std::string& line, std::vector<std::string>& out) {
  out.clear();
  std::string field;
  bool quoted = false, was_quoted = false;
  auto push = [&] {
    out.push_back(was_quoted ? field : trimmed(field));
    field.clear();
    was_quoted = false;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') {
        field += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (c == '"' && trimmed(field).empty() && !was_quoted) {
      quoted = was_quoted = true;
      field.clear();
    } else if (c == ',') {
      push();
    } else if (!was_quoted) {
      field += c;
    }
  }
  if (quoted) return false;
  push();
  return true;
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    throw InputError(fmt::format("cannot read CSV file '{}': {}", path.string(),
                                 std::filesystem::exists(path) ? "it is not readable" : "no such file"));
  }
  std::stringstream s;
  s << in.rdbuf();
  return parse(s.str(), path.string());
}

CsvTable CsvTable::parse(const std::string& text, const std::string& source) {
  CsvTable t;
  t.source_ = source;
  // A spreadsheet's UTF-8 export may start with a byte-order mark: not part of the first column's name.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  std::istringstream in(text.compare(0, kByteOrderMark.size(), kByteOrderMark) == 0 ? text.substr(kByteOrderMark.size())
                                                                                    : text);
  std::string line;
  std::vector<std::string> fields;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (line[line.find_first_not_of(" \t")] == '#') {
      t.comments_.push_back(trimmed(line.substr(line.find('#') + 1)));
      continue;
    }
    if (!split_record(line, fields))
      throw InputError(fmt::format("{}:{}: a quoted field is not closed; end it with '\"'", source, number));
    if (t.header_.empty()) {
      t.header_ = fields;
      continue;
    }
    if (fields.size() != t.header_.size())
      throw InputError(fmt::format("{}:{}: {} fields, but the header has {} ({})", source, number, fields.size(),
                                   t.header_.size(), join(t.header_)));
    t.cells_.push_back(fields);
    t.lines_.push_back(number);
  }
  if (t.header_.empty())
    throw InputError(fmt::format("{}: no header row (the first line that is not a # comment)", source));
  return t;
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return i;
  std::string msg = fmt::format("{}: no column '{}'", source_, name);
  if (auto best = closest_match(name, header_)) msg += fmt::format("; did you mean '{}'?", *best);
  throw InputError(msg + fmt::format(" (columns: {})", join(header_)));
}

const std::string& CsvTable::text(std::size_t row, const std::string& name) const {
  return cells_.at(row).at(column(name));
}

double CsvTable::number(std::size_t row, const std::string& name) const {
  const std::string& s = text(row, name);
  double v = 0;
  const char* last = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), last, v);
  if (s.empty() || ec != std::errc() || ptr != last || !std::isfinite(v))
    throw InputError(fmt::format("{}:{}: column '{}' = '{}': expected a number", source_, lines_.at(row), name, s));
  return v;
}

std::vector<double> CsvTable::numbers(const std::string& name) const {
  std::vector<double> out;
  out.reserve(rows());
  for (std::size_t r = 0; r < rows(); ++r) out.push_back(number(r, name));
  return out;
}

std::size_t CsvTable::find_row(const std::string& name, const std::string& value) const {
  const std::size_t c = column(name);
  std::vector<std::string> values;
  for (std::size_t r = 0; r < rows(); ++r) {
    if (cells_[r][c] == value) return r;
    values.push_back(cells_[r][c]);
  }
  std::string msg = fmt::format("{}: no row with {} = '{}'", source_, name, value);
  if (auto best = closest_match(value, values)) msg += fmt::format("; did you mean '{}'?", *best);
  throw InputError(msg + fmt::format(" ({} values: {})", name, join(values)));
}

std::string csv_field(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  const bool quote = text.find_first_of(",\"") != std::string::npos ||
                     (!text.empty() && (std::isspace(static_cast<unsigned char>(text.front())) ||
                                        std::isspace(static_cast<unsigned char>(text.back()))));
  if (!quote) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace suite::io
