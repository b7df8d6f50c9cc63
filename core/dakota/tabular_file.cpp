#include "core/dakota/tabular_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string_view>

#include "core/errors.hpp"

namespace suite::dakota {
namespace {

constexpr int kLabelWidth = 14;          // setw(14) for every variable and response label
constexpr int kEvalIdLabelWidth = 7;     // header: setw(7) << std::left << "eval_id"
constexpr int kInterfaceLabelWidth = 8;  // header: setw(8) << std::left << "interface"
constexpr int kEvalIdWidth = 8;          // rows: setw(8) << std::left << eval_id
constexpr int kInterfaceWidth = 10;      // rows: setw(10) << std::left << iface_id

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

void append_left(std::string& out, std::string_view s, int width) {
  out += s;
  if (s.size() < static_cast<std::size_t>(width)) out.append(static_cast<std::size_t>(width) - s.size(), ' ');
  out += ' ';
}

// Dakota's default float format with setprecision(precision): "%.<precision>g".
std::string general(double value, int precision) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
  return buffer;
}

void check_labels(const std::vector<std::string>& labels, std::string_view what) {
  for (const auto& l : labels)
    if (l.empty() || std::any_of(l.begin(), l.end(), is_space))
      throw InputError(
          fmt::format("Dakota tabular file: {} label \"{}\" must be non-empty and without white space", what, l));
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    if (is_space(line[i])) {
      ++i;
      continue;
    }
    const auto start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    out.push_back(line.substr(start, i - start));
  }
  return out;
}

// A table value: a number, or N/A (not computed) and nan (a NaN recovery value) as NaN.
std::optional<double> parse_value(std::string_view s) {
  if (s == "N/A") return std::numeric_limits<double>::quiet_NaN();
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size() || (ec != std::errc() && ec != std::errc::result_out_of_range)) return std::nullopt;
  if (ec == std::errc::result_out_of_range) value = std::strtod(std::string(s).c_str(), nullptr);
  return value;
}

[[noreturn]] void fail(const std::string& source, int line, const std::string& message) {
  throw InputError(fmt::format("{}:{}: {}", source, line, message));
}

}  // namespace

TabularWriter::TabularWriter(std::ostream& out, std::vector<std::string> variables, std::vector<std::string> responses,
                             bool with_interface, int precision)
    : out_(out),
      num_variables_(variables.size()),
      num_responses_(responses.size()),
      with_interface_(with_interface),
      precision_(precision) {
  check_labels(variables, "variable");
  check_labels(responses, "response");
  if (precision < 1 || precision > 17)
    throw InputError(fmt::format("Dakota tabular file: precision {} is not in 1..17", precision));
  std::string line = "%";
  append_left(line, "eval_id", kEvalIdLabelWidth);
  if (with_interface_) append_left(line, "interface", kInterfaceLabelWidth);
  for (const auto& v : variables) append_left(line, v, kLabelWidth);
  for (const auto& r : responses) append_left(line, r, kLabelWidth);
  line += '\n';
  out_ << line << std::flush;
}

void TabularWriter::row(long eval_id, const std::string& interface_id, const std::vector<double>& variables,
                        const std::vector<double>& responses) {
  if (variables.size() != num_variables_ || responses.size() != num_responses_)
    throw InputError(fmt::format("Dakota tabular file: row {} has {} variables and {} responses, the header {} and {}",
                                 eval_id, variables.size(), responses.size(), num_variables_, num_responses_));
  if (std::any_of(interface_id.begin(), interface_id.end(), is_space))
    throw InputError(
        fmt::format("Dakota tabular file: interface id \"{}\" must not contain white space", interface_id));
  std::string line;
  append_left(line, std::to_string(eval_id), kEvalIdWidth);
  if (with_interface_) append_left(line, interface_id.empty() ? "NO_ID" : interface_id, kInterfaceWidth);
  for (double v : variables) append_left(line, general(v, precision_), precision_ + 4);
  for (double r : responses) append_left(line, general(r, precision_), precision_ + 4);
  line += '\n';
  out_ << line << std::flush;
}

std::vector<Row> read_tabular(const std::string& text, const std::string& source_name, std::size_t num_variables,
                              bool with_interface) {
  std::vector<Row> rows;
  const std::size_t lead = with_interface ? 2 : 1;
  std::size_t columns = 0;
  bool have_header = false;
  int number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = std::min(text.find('\n', start), text.size());
    ++number;
    const auto fields = words(std::string_view(text).substr(start, end - start));
    start = end + 1;
    if (fields.empty()) continue;
    if (!have_header) {
      const bool eval_ok = fields[0] == "%eval_id";
      const bool iface_ok = !with_interface || (fields.size() > 1 && fields[1] == "interface");
      if (!eval_ok || !iface_ok)
        fail(source_name, number,
             fmt::format("expected the annotated header \"%eval_id {}<variables> <responses>\"",
                         with_interface ? "interface " : ""));
      if (fields.size() < lead + num_variables)
        fail(source_name, number,
             fmt::format("the header has {} labels after the id columns, fewer than the {} variables",
                         fields.size() - lead, num_variables));
      columns = fields.size();
      have_header = true;
      continue;
    }
    if (fields.size() != columns)
      fail(source_name, number, fmt::format("expected {} columns as in the header, found {}", columns, fields.size()));
    Row row;
    const auto id = fields[0];
    const auto [id_end, id_ec] = std::from_chars(id.data(), id.data() + id.size(), row.eval_id);
    if (id_ec != std::errc() || id_end != id.data() + id.size())
      fail(source_name, number, fmt::format("the evaluation id \"{}\" is not an integer", id));
    if (with_interface && fields[1] != "NO_ID" && fields[1] != "EMPTY") row.interface_id = std::string(fields[1]);
    for (std::size_t c = lead; c < columns; ++c) {
      const auto value = parse_value(fields[c]);
      if (!value)
        fail(source_name, number, fmt::format("column {} \"{}\" is not a number (nor N/A)", c + 1, fields[c]));
      (c < lead + num_variables ? row.variables : row.responses).push_back(*value);
    }
    rows.push_back(std::move(row));
  }
  if (!have_header) fail(source_name, std::max(number, 1), "empty file: the \"%eval_id ...\" header is missing");
  return rows;
}

}  // namespace suite::dakota
