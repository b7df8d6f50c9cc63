#include "core/dakota/results_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string_view>

#include "core/errors.hpp"

namespace suite::dakota {
namespace {

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

struct Token {
  std::string_view text;
  int line;
};

std::vector<Token> tokens(const std::string& text) {
  std::vector<Token> out;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    if (is_space(text[i])) {
      if (text[i] == '\n') ++line;
      ++i;
      continue;
    }
    const auto start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    out.push_back({std::string_view(text).substr(start, i - start), line});
  }
  return out;
}

// A whole word read as a number (Dakota checks with isfloat, then uses atof); out-of-range
// values come back as strtod gives them (infinity, or an underflow towards zero).
std::optional<double> parse_number(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size() || (ec != std::errc() && ec != std::errc::result_out_of_range)) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return std::strtod(std::string(s).c_str(), nullptr);
  return value;
}

[[noreturn]] void fail(const std::string& source, int line, const std::string& message) {
  throw InputError(fmt::format("{}:{}: {}", source, line, message));
}

// Dakota's Response::failure_reported: first non-blank characters "fail", any case.
bool failure_reported(const std::string& text) {
  const auto start = std::find_if_not(text.begin(), text.end(), is_space);
  if (text.end() - start < 4) return false;
  return std::equal(start, start + 4, "fail",
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

}  // namespace

Results read_results(const std::string& text, const std::string& source_name, std::size_t expected) {
  Results r;
  if (failure_reported(text)) {
    r.failed = true;
    return r;
  }
  const auto all = tokens(text);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& [word, line] = all[i];
    if (word.front() == '[')
      fail(source_name, line, "gradient or Hessian data (\"[\") found; only function values are requested");
    const auto value = parse_number(word);
    if (!value)
      fail(source_name, line,
           fmt::format("\"{}\" is not a number; expected a function value, optionally followed by a label", word));
    if (!std::isfinite(*value))
      fail(source_name, line, fmt::format("function value \"{}\" is not a finite number", word));
    if (r.values.size() == expected)
      fail(source_name, line, fmt::format("more function values than the {} expected (\"{}\")", expected, word));
    r.values.push_back(*value);
    // A following word that is not a number (nor "[") labels this value.
    if (i + 1 < all.size() && all[i + 1].text.front() != '[' && !parse_number(all[i + 1].text)) {
      r.labels.emplace_back(all[i + 1].text);
      ++i;
    } else {
      r.labels.emplace_back();
    }
  }
  if (r.values.size() < expected)
    fail(source_name, all.empty() ? 1 : all.back().line,
         fmt::format("expected {} function value(s) but found {} (or \"FAIL\" for a failed evaluation)", expected,
                     r.values.size()));
  return r;
}

std::string write_results(const std::vector<std::pair<std::string, double>>& labelled_values) {
  std::string out;
  for (const auto& [label, value] : labelled_values) {
    if (std::any_of(label.begin(), label.end(), is_space))
      throw InputError(fmt::format("Dakota results file: label \"{}\" must not contain white space", label));
    if (!std::isfinite(value))
      throw InputError(
          fmt::format("Dakota results file: the value of \"{}\" is not finite ({}); report a failed evaluation instead",
                      label, value));
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%24.16E", value);
    out += label.empty() ? fmt::format("{}\n", buffer) : fmt::format("{} {}\n", buffer, label);
  }
  return out;
}

std::string write_failure() {
  return "FAIL\n";
}

}  // namespace suite::dakota
