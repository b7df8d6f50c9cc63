#include "core/dakota/parameters_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <string_view>

#include "core/errors.hpp"

namespace suite::dakota {
namespace {

// Field widths of Dakota's writers (write_precision 15, w = write_precision + 7).
constexpr int kValueWidth = 22;
constexpr int kApreproTagWidth = 15;
constexpr std::string_view kStandardIndent = "                     ";  // 21 spaces
constexpr std::string_view kApreproIndent = "                    ";    // 20 spaces

// The section headers: standard tag, APREPRO tag.
struct Header {
  std::string_view standard;
  std::string_view aprepro;
};
constexpr Header kVariables{"variables", "DAKOTA_VARS"};
constexpr Header kFunctions{"functions", "DAKOTA_FNS"};
constexpr Header kDerivatives{"derivative_variables", "DAKOTA_DER_VARS"};
constexpr Header kComponents{"analysis_components", "DAKOTA_AN_COMPS"};
constexpr Header kEvalId{"eval_id", "DAKOTA_EVAL_ID"};
constexpr Header kMetadata{"metadata", "DAKOTA_METADATA"};

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}
bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

bool has_space(std::string_view s) {
  return std::any_of(s.begin(), s.end(), is_space);
}

bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), is_digit);
}

// A count or id: digits only, no overflow.
std::optional<std::size_t> parse_count(std::string_view s) {
  std::size_t value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (!all_digits(s) || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return value;
}

// "1", "1:2", "1:2:3": what Dakota writes as the evaluation ID.
bool valid_eval_id(std::string_view s) {
  std::size_t start = 0;
  while (true) {
    const auto colon = s.find(':', start);
    if (!all_digits(s.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start)))
      return false;
    if (colon == std::string_view::npos) return true;
    start = colon + 1;
  }
}

std::string pad_left(std::string_view s, int width) {
  const auto n = static_cast<std::size_t>(width);
  return s.size() >= n ? std::string(s) : std::string(n - s.size(), ' ') + std::string(s);
}

std::string pad_right(std::string_view s, int width) {
  const auto n = static_cast<std::size_t>(width);
  return s.size() >= n ? std::string(s) : std::string(s) + std::string(n - s.size(), ' ');
}

// std::scientific with precision 15, as Dakota's iostreams write it ("%.15e").
std::string scientific(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.15e", value);
  return buffer;
}

// A real number as Dakota writes it; nullopt unless the whole token is a finite number (an
// underflow reads as strtod gives it).
std::optional<double> parse_real(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size() || (ec != std::errc() && ec != std::errc::result_out_of_range)) return std::nullopt;
  if (ec == std::errc::result_out_of_range) value = std::strtod(std::string(s).c_str(), nullptr);
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

// Writes lines of one layout.
class Writer {
 public:
  explicit Writer(ParametersFormat format) : format_(format) {}

  // A numeric or unquoted field with its tag.
  void item(std::string_view value, std::string_view tag) {
    if (format_ == ParametersFormat::standard) {
      out_ += fmt::format("{}{} {}\n", kStandardIndent, pad_left(value, kValueWidth), tag);
    } else {
      out_ += fmt::format("{}{{ {} = {} }}\n", kApreproIndent, pad_right(tag, kApreproTagWidth),
                          pad_left(value, kValueWidth));
    }
  }

  // A string field: APREPRO quotes it, and setw(22) applies to the opening quote only
  // (array_write_aprepro for StringArray in dakota_data_io.hpp).
  void text(std::string_view value, std::string_view tag) {
    if (format_ == ParametersFormat::standard) {
      item(value, tag);
    } else {
      out_ += fmt::format("{}{{ {} = {}{}\" }}\n", kApreproIndent, pad_right(tag, kApreproTagWidth),
                          pad_left("\"", kValueWidth), value);
    }
  }

  void header(const Header& h, std::size_t count) {
    item(std::to_string(count), format_ == ParametersFormat::standard ? h.standard : h.aprepro);
  }

  std::string take() { return std::move(out_); }

 private:
  ParametersFormat format_;
  std::string out_;
};

void check_name(std::string_view name, std::string_view what) {
  if (name.empty() || has_space(name))
    throw InputError(
        fmt::format("Dakota parameters file: {} \"{}\" must be non-empty and without white space", what, name));
}

void check_text(std::string_view value, std::string_view what, ParametersFormat format) {
  if (value.empty() || value != trim(value) || value.find('\n') != std::string_view::npos ||
      (format == ParametersFormat::aprepro && value.find('"') != std::string_view::npos))
    throw InputError(fmt::format(
        "Dakota parameters file: {} \"{}\" must be non-empty, one line, without leading or trailing white space{}",
        what, value, format == ParametersFormat::aprepro ? " and without '\"'" : ""));
}

// ---- reading ----

struct Entry {
  std::string value;
  std::string tag;
  int line = 0;
  bool quoted = false;  // APREPRO string value
};

class Reader {
 public:
  Reader(const std::string& text, const std::string& source) : source_(source) {
    std::size_t start = 0;
    int number = 0;
    while (start <= text.size()) {
      const auto end = std::min(text.find('\n', start), text.size());
      ++number;
      const auto line = trim(std::string_view(text).substr(start, end - start));
      if (!line.empty()) lines_.push_back({std::string(line), number});
      start = end + 1;
    }
    format_ =
        !lines_.empty() && lines_.front().text.front() == '{' ? ParametersFormat::aprepro : ParametersFormat::standard;
  }

  ParametersFormat format() const { return format_; }
  bool done() const { return next_ >= lines_.size(); }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw InputError(fmt::format("{}:{}: {}", source_, line, message));
  }

  int last_line() const { return lines_.empty() ? 1 : lines_.back().number; }

  // The next line as (value, tag).
  Entry entry(std::string_view what) {
    if (done()) fail(last_line(), fmt::format("the file ends where {} was expected (is it complete?)", what));
    const auto& [text, number] = lines_[next_++];
    return format_ == ParametersFormat::standard ? standard_entry(text, number, what)
                                                 : aprepro_entry(text, number, what);
  }

  // A header line "<count> <tag>"; returns the count.
  std::size_t header(const Header& h) {
    const auto tag = format_ == ParametersFormat::standard ? h.standard : h.aprepro;
    const auto e = entry(fmt::format("the \"{}\" line", tag));
    const auto count = parse_count(e.value);
    if (e.tag != tag || !count) fail(e.line, expected_header(h, e));
    return *count;
  }

  std::string expected_header(const Header& h, const Entry& e) const {
    return format_ == ParametersFormat::standard
               ? fmt::format("expected \"<count> {}\", found \"{} {}\"", h.standard, e.value, e.tag)
               : fmt::format("expected \"{{ {} = <count> }}\", found \"{{ {} = {} }}\"", h.aprepro, e.tag, e.value);
  }

  // True if the next line has the tag of header `h` (without consuming it).
  bool next_is(const Header& h) const {
    if (done()) return false;
    const auto& [text, number] = lines_[next_];
    const auto e = format_ == ParametersFormat::standard ? standard_entry(text, number, "a header")
                                                         : aprepro_entry(text, number, "a header");
    return e.tag == (format_ == ParametersFormat::standard ? h.standard : h.aprepro);
  }

  int next_line() const { return done() ? last_line() : lines_[next_].number; }

 private:
  struct Line {
    std::string text;
    int number;
  };

  // "<value> <tag>": the tag is the last word; the value (a string may hold spaces) the rest.
  Entry standard_entry(const std::string& text, int number, std::string_view what) const {
    const auto split = std::find_if(text.rbegin(), text.rend(), is_space);
    if (split == text.rend()) fail(number, fmt::format("expected \"<value> <tag>\" for {}, found \"{}\"", what, text));
    const auto at = static_cast<std::size_t>(text.rend() - split);  // index just past the space
    return {std::string(trim(std::string_view(text).substr(0, at))), text.substr(at), number, false};
  }

  // "{ <tag> = <value> }", the value possibly in double quotes.
  Entry aprepro_entry(const std::string& text, int number, std::string_view what) const {
    const auto eq = text.find('=');
    if (text.front() != '{' || text.back() != '}' || text.size() < 2 || eq == std::string::npos)
      fail(number, fmt::format("expected \"{{ <tag> = <value> }}\" for {}, found \"{}\"", what, text));
    const std::string_view body(text);
    Entry e{std::string(trim(body.substr(eq + 1, body.size() - 1 - (eq + 1)))),
            std::string(trim(body.substr(1, eq - 1))), number, false};
    if (!e.value.empty() && e.value.front() == '"') {
      if (e.value.size() < 2 || e.value.back() != '"')
        fail(number, fmt::format("unterminated quoted value for {} in \"{}\"", what, text));
      e.value = e.value.substr(1, e.value.size() - 2);
      e.quoted = true;
    }
    if (e.tag.empty()) fail(number, fmt::format("missing tag for {} in \"{}\"", what, text));
    return e;
  }

  std::string source_;
  std::vector<Line> lines_;
  std::size_t next_ = 0;
  ParametersFormat format_;
};

// "<prefix><digits>" or "<prefix><digits>:<rest>"; returns the rest ("" without a colon),
// nullopt if the tag does not have that form.
std::optional<std::string> tag_suffix(std::string_view tag, std::string_view prefix) {
  if (!tag.starts_with(prefix)) return std::nullopt;
  tag.remove_prefix(prefix.size());
  const auto colon = tag.find(':');
  if (!all_digits(tag.substr(0, colon))) return std::nullopt;
  return colon == std::string_view::npos ? std::string() : std::string(tag.substr(colon + 1));
}

}  // namespace

std::string write_parameters(const Parameters& p, ParametersFormat format) {
  std::set<std::string> seen;
  for (const auto& [name, value] : p.variables) {
    check_name(name, "variable name");
    if (!seen.insert(name).second)
      throw InputError(fmt::format("Dakota parameters file: variable \"{}\" appears twice", name));
    if (!std::isfinite(value))
      throw InputError(fmt::format("Dakota parameters file: variable \"{}\" is not finite ({})", name, value));
  }
  for (const auto& r : p.responses) check_name(r, "response descriptor");
  if (!p.asv.empty() && p.asv.size() != p.responses.size())
    throw InputError(
        fmt::format("Dakota parameters file: {} ASV entries for {} responses", p.asv.size(), p.responses.size()));
  for (int a : p.asv)
    if (a < 0 || a > 7) throw InputError(fmt::format("Dakota parameters file: ASV value {} is not in 0..7", a));
  for (const auto& c : p.analysis_components) check_text(c, "analysis component", format);
  if (!p.analysis_driver.empty()) check_name(p.analysis_driver, "analysis driver");
  for (const auto& m : p.metadata) check_text(m, "metadata descriptor", format);
  if (!valid_eval_id(p.eval_id))
    throw InputError(fmt::format("Dakota parameters file: eval_id \"{}\" is not like \"1\" or \"1:2\"", p.eval_id));

  // Derivative variables as 1-based positions among the variables.
  std::vector<std::pair<std::size_t, std::string>> dvv;
  if (p.derivative_variables.empty()) {
    for (std::size_t i = 0; i < p.variables.size(); ++i) dvv.emplace_back(i + 1, p.variables[i].first);
  } else {
    for (const auto& name : p.derivative_variables) {
      const auto it =
          std::find_if(p.variables.begin(), p.variables.end(), [&](const auto& v) { return v.first == name; });
      if (it == p.variables.end())
        throw InputError(
            fmt::format("Dakota parameters file: derivative variable \"{}\" is not one of the variables", name));
      dvv.emplace_back(static_cast<std::size_t>(it - p.variables.begin()) + 1, name);
    }
  }

  Writer w(format);
  w.header(kVariables, p.variables.size());
  for (const auto& [name, value] : p.variables) {
    const auto text = scientific(value);
    if (!parse_real(text))  // 16 digits round the largest doubles up past the range
      throw InputError(fmt::format(
          "Dakota parameters file: variable \"{}\" ({}) is too close to the largest double to write", name, text));
    w.item(text, name);
  }
  w.header(kFunctions, p.responses.size());
  for (std::size_t i = 0; i < p.responses.size(); ++i)
    w.item(std::to_string(p.asv.empty() ? 1 : p.asv[i]), fmt::format("ASV_{}:{}", i + 1, p.responses[i]));
  w.header(kDerivatives, dvv.size());
  for (std::size_t i = 0; i < dvv.size(); ++i)
    w.item(std::to_string(dvv[i].first), fmt::format("DVV_{}:{}", i + 1, dvv[i].second));
  w.header(kComponents, p.analysis_components.size());
  const std::string driver = p.analysis_driver.empty() ? "" : ":" + p.analysis_driver;
  for (std::size_t i = 0; i < p.analysis_components.size(); ++i)
    w.text(p.analysis_components[i], fmt::format("AC_{}{}", i + 1, driver));
  w.item(p.eval_id, format == ParametersFormat::standard ? kEvalId.standard : kEvalId.aprepro);
  w.header(kMetadata, p.metadata.size());
  for (std::size_t i = 0; i < p.metadata.size(); ++i) w.text(p.metadata[i], fmt::format("MD_{}", i + 1));
  return w.take();
}

ParametersFormat detect_parameters_format(const std::string& text) {
  return Reader(text, "").format();
}

Parameters read_parameters(const std::string& text, const std::string& source_name) {
  Reader in(text, source_name);
  Parameters p;
  std::set<std::string> seen;

  const auto num_variables = in.header(kVariables);
  for (std::size_t i = 0; i < num_variables; ++i) {
    const auto e = in.entry(fmt::format("variable {} of {}", i + 1, num_variables));
    const auto value = e.quoted ? std::nullopt : parse_real(e.value);
    if (!value)
      in.fail(e.line, fmt::format("the value \"{}\" of variable \"{}\" is not a finite real number "
                                  "(string-valued variables are not supported)",
                                  e.value, e.tag));
    if (!seen.insert(e.tag).second) in.fail(e.line, fmt::format("variable \"{}\" appears twice", e.tag));
    p.variables.emplace_back(e.tag, *value);
  }

  const auto num_functions = in.header(kFunctions);
  for (std::size_t i = 0; i < num_functions; ++i) {
    const auto e = in.entry(fmt::format("the ASV of function {} of {}", i + 1, num_functions));
    const auto name = tag_suffix(e.tag, "ASV_");
    if (!name || name->empty())
      in.fail(e.line, fmt::format("expected the tag \"ASV_{}:<response>\", found \"{}\"", i + 1, e.tag));
    if (e.value.size() != 1 || e.value[0] < '0' || e.value[0] > '7')
      in.fail(e.line, fmt::format("the ASV \"{}\" of response \"{}\" is not an integer in 0..7", e.value, *name));
    p.responses.push_back(*name);
    p.asv.push_back(e.value[0] - '0');
  }

  const auto num_derivatives = in.header(kDerivatives);
  for (std::size_t i = 0; i < num_derivatives; ++i) {
    const auto e = in.entry(fmt::format("derivative variable {} of {}", i + 1, num_derivatives));
    auto name = tag_suffix(e.tag, "DVV_");
    if (!name) in.fail(e.line, fmt::format("expected the tag \"DVV_{}:<variable>\", found \"{}\"", i + 1, e.tag));
    const auto position = parse_count(e.value);
    if (!position || *position == 0 || *position > p.variables.size())
      in.fail(e.line,
              fmt::format("the derivative variable id \"{}\" is not between 1 and {}", e.value, p.variables.size()));
    // Dakota omits ":<name>" when the id is not an active continuous variable; the position names it then.
    if (name->empty()) *name = p.variables[*position - 1].first;
    p.derivative_variables.push_back(*name);
  }

  const auto num_components = in.header(kComponents);
  for (std::size_t i = 0; i < num_components; ++i) {
    const auto e = in.entry(fmt::format("analysis component {} of {}", i + 1, num_components));
    const auto driver = tag_suffix(e.tag, "AC_");
    if (!driver) in.fail(e.line, fmt::format("expected the tag \"AC_{}[:<driver>]\", found \"{}\"", i + 1, e.tag));
    if (p.analysis_driver.empty()) p.analysis_driver = *driver;
    p.analysis_components.push_back(e.value);
  }

  const auto id = in.entry("the eval_id line");
  const auto id_tag = in.format() == ParametersFormat::standard ? kEvalId.standard : kEvalId.aprepro;
  if (id.tag != id_tag || !valid_eval_id(id.value))
    in.fail(id.line,
            fmt::format("expected the evaluation id (\"1\" or \"1:2\") tagged \"{}\", found \"{}\" tagged \"{}\"",
                        id_tag, id.value, id.tag));
  p.eval_id = id.value;

  // Dakota 6.16 and newer add the metadata block.
  if (in.next_is(kMetadata)) {
    const auto num_metadata = in.header(kMetadata);
    for (std::size_t i = 0; i < num_metadata; ++i) {
      const auto e = in.entry(fmt::format("metadata descriptor {} of {}", i + 1, num_metadata));
      if (!tag_suffix(e.tag, "MD_") || e.tag.find(':') != std::string::npos)
        in.fail(e.line, fmt::format("expected the tag \"MD_{}\", found \"{}\"", i + 1, e.tag));
      p.metadata.push_back(e.value);
    }
  }

  if (!in.done()) {
    if (in.next_is(kVariables))
      in.fail(in.next_line(), "a second evaluation follows: batch parameters files are not supported");
    in.fail(in.next_line(), "unexpected text after the last section (eval_id or metadata)");
  }
  return p;
}

}  // namespace suite::dakota
