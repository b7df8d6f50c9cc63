#include "core/config/config.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/config/suggest.hpp"
#include "core/config/units.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::config {

struct State {
  std::string source;
  std::filesystem::path base_dir;  // relative file paths in the tree are read from here
  YAML::Node root;
  std::map<std::string, std::set<std::string>> requested;  // section path -> keys asked for
  std::set<std::string> free_form;                         // subtrees passed on unchecked
  std::map<std::string, std::string> overridden;           // key path -> "key=value" argument
  std::string override_origin = "command-line override";   // what messages call an override
  std::map<std::string, std::string> resolved;             // key path -> value as the program read it
};

namespace {

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string one_line(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "";
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

// "file:line:col" of a node, or the override that set it.
std::string location(const State& s, const std::string& path, const YAML::Mark& mark) {
  // The key itself or a section above it may come from an override ("output={every: 5}").
  for (std::string p = path; !p.empty();) {
    if (auto it = s.overridden.find(p); it != s.overridden.end())
      return fmt::format("{} '{}'", s.override_origin, it->second);
    const auto cut = p.find_last_of(".[");
    p = cut == std::string::npos ? "" : p.substr(0, cut);
  }
  if (mark.is_null()) return s.source;
  return fmt::format("{}:{}:{}", s.source, mark.line + 1, mark.column + 1);
}

std::string fmt_g(double v) {
  return fmt::format("{:g}", v);
}

// Values as resolved() records them: numbers in the shortest form that reads back to the same
// bits, so that two configurations that mean the same thing ("2 m", "200 cm") record the same
// text and any change shows.
std::string exact(double v) {
  return fmt::format("{}", v);
}
std::string exact(double v, const std::string& unit) {
  return unit.empty() || unit == "1" ? exact(v) : exact(v) + " " + unit;
}
template <class T>
std::string resolved_text(const T& v) {
  if constexpr (std::is_same_v<T, double>) {
    return exact(v);
  } else if constexpr (std::is_same_v<T, bool>) {
    return v ? "true" : "false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(v);
  } else {
    std::string out = "[";
    for (const auto& e : v) out += (out.size() > 1 ? ", " : "") + resolved_text(e);
    return out + "]";
  }
}

// A file's content as resolved() records it: its size and 64-bit FNV-1a digest, so that a
// changed file shows and a moved one does not.
std::string content_digest(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::uint64_t hash = 14695981039346656037ULL, size = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      hash ^= static_cast<unsigned char>(buffer[i]);
      hash *= 1099511628211ULL;
    }
    size += static_cast<std::uint64_t>(in.gcount());
  }
  return fmt::format("a file of {} bytes, FNV-1a {:016x}", size, hash);
}

bool parse_double(std::string_view text, double& out, std::size_t& used) {
  while (!text.empty() && text.front() == '+') text.remove_prefix(1);
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec != std::errc()) return false;
  used = static_cast<std::size_t>(ptr - text.data());
  return true;
}

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// yaml-cpp keeps duplicate keys silently; a strict reader rejects them.
void reject_duplicate_keys(const State& s, const YAML::Node& n, const std::string& path) {
  if (n.IsMap()) {
    std::map<std::string, int> seen;
    for (const auto& kv : n) {
      const std::string key = kv.first.Scalar();
      const std::string p = join_path(path, key);
      if (auto [it, fresh] = seen.emplace(key, kv.first.Mark().line + 1); !fresh) {
        throw InputError(fmt::format("{}: key '{}' appears twice (first on line {}); keep one of them",
                                     location(s, p, kv.first.Mark()), p, it->second));
      }
      reject_duplicate_keys(s, kv.second, p);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) reject_duplicate_keys(s, n[i], fmt::format("{}[{}]", path, i));
  }
}

void apply_override(State& s, const std::string& arg) {
  const auto eq = arg.find('=');
  const std::string key_path = trim(std::string_view(arg).substr(0, eq));
  const std::string value = eq == std::string::npos ? "" : trim(std::string_view(arg).substr(eq + 1));
  auto bad = [&](const std::string& why) {
    return InputError(fmt::format("{} '{}': {}; write it as key.path=value", s.override_origin, arg, why));
  };
  if (eq == std::string::npos || key_path.empty()) throw bad("it has no '='");
  if (value.empty()) throw bad("it has no value after '='");
  std::vector<std::string> segments;
  for (std::size_t start = 0;;) {
    const auto dot = key_path.find('.', start);
    segments.push_back(key_path.substr(start, dot - start));
    if (segments.back().empty()) throw bad("the key path has an empty part");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node parsed;
  try {
    parsed = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw bad(fmt::format("the value is not valid YAML ({})", e.msg));
  }
  YAML::Node cur = s.root;
  std::string path;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string& seg = segments[i];
    const bool last = i + 1 == segments.size();
    if (cur.IsSequence()) {
      std::size_t idx = 0;
      auto [p, ec] = std::from_chars(seg.data(), seg.data() + seg.size(), idx);
      if (ec != std::errc() || p != seg.data() + seg.size() || idx >= cur.size())
        throw bad(fmt::format("'{}' is a list of {} entries; use an index 0..{}", path, cur.size(),
                              cur.size() == 0 ? 0 : cur.size() - 1));
      path += fmt::format("[{}]", idx);
      if (last) {
        cur[idx] = parsed;
      } else {
        YAML::Node next = cur[idx];
        cur.reset(next);  // rebind; operator= would overwrite the node's contents
      }
      continue;
    }
    if (!cur.IsMap() && !cur.IsNull()) throw bad(fmt::format("'{}' holds a value, not a section", path));
    path = join_path(path, seg);
    if (last) {
      cur[seg] = parsed;
    } else {
      YAML::Node next = cur[seg];
      if (!next.IsDefined() || next.IsNull()) {
        cur[seg] = YAML::Node(YAML::NodeType::Map);
        next.reset(cur[seg]);
      }
      cur.reset(next);
    }
  }
  s.overridden[path] = arg;
}

std::shared_ptr<State> load(const std::string& text, const std::string& source,
                            const std::vector<std::string>& overrides, const std::string& override_origin) {
  auto s = std::make_shared<State>();
  s->source = source;
  s->override_origin = override_origin;
  try {
    s->root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", source, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!s->root.IsDefined() || s->root.IsNull()) {
    s->root = YAML::Node(YAML::NodeType::Map);
  } else if (!s->root.IsMap()) {
    throw InputError(fmt::format("{}: the file must be a mapping of keys (key: value lines), not a {}", source,
                                 s->root.IsSequence() ? "list" : "single value"));
  }
  reject_duplicate_keys(*s, s->root, "");
  for (const auto& o : overrides) apply_override(*s, o);
  return s;
}

void check_known(const State& s, const YAML::Node& n, const std::string& path) {
  if (s.free_form.count(path)) return;
  if (n.IsMap()) {
    auto it = s.requested.find(path);
    const std::set<std::string> none;
    const std::set<std::string>& asked = it == s.requested.end() ? none : it->second;
    for (const auto& kv : n) {
      const std::string key = kv.first.Scalar();
      const std::string p = join_path(path, key);
      if (!asked.count(key)) {
        const std::vector<std::string> valid(asked.begin(), asked.end());
        std::string msg = fmt::format("{}: unknown key '{}'", location(s, p, kv.first.Mark()), p);
        if (auto best = closest_match(key, valid)) msg += fmt::format("; did you mean '{}'?", *best);
        if (valid.empty()) {
          msg += path.empty() ? "; this file takes no keys here" : fmt::format("; '{}' takes no keys", path);
        } else {
          msg +=
              fmt::format(" (valid {}: {})", path.empty() ? "top-level keys" : "keys in '" + path + "'", join(valid));
        }
        throw InputError(msg);
      }
      check_known(s, kv.second, p);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) check_known(s, n[i], fmt::format("{}[{}]", path, i));
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------- Range

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool lo = min_open ? v > min : v >= min;
  const bool hi = max_open ? v < max : v <= max;
  return lo && hi;
}

std::string Range::describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}", min_open ? '(' : '[', fmt_g(min), fmt_g(max), max_open ? ')' : ']');
  if (has_min) return fmt::format("{} {}", min_open ? ">" : ">=", fmt_g(min));
  if (has_max) return fmt::format("{} {}", max_open ? "<" : "<=", fmt_g(max));
  return "a finite number";
}

// -------------------------------------------------------------------------------------- Section

Section::Section(std::shared_ptr<State> state, std::shared_ptr<YAML::Node> node, std::string path)
    : state_(std::move(state)), node_(std::move(node)), path_(std::move(path)) {}

std::string Section::child_path(const std::string& key) const {
  return join_path(path_, key);
}

YAML::Node Section::child(const std::string& key) const {
  state_->requested[path_].insert(key);
  const YAML::Node& self = *node_;
  return self[key];
}

void Section::reject(const std::string& key, const std::string& problem) const {
  const std::string p = child_path(key);
  const YAML::Node n = static_cast<const YAML::Node&>(*node_)[key];
  if (!n.IsDefined()) {
    throw InputError(fmt::format("{}: {}", location(*state_, path_, node_->Mark()), problem));
  }
  throw InputError(fmt::format("{}: key '{}' = '{}': {}", location(*state_, p, n.Mark()), p, one_line(n), problem));
}

bool Section::has(const std::string& key) const {
  const YAML::Node n = child(key);
  return n.IsDefined() && !n.IsNull();
}

void Section::store_default(const std::string& key, const YAML::Node& value) const {
  (*node_)[key] = value;
}

void Section::resolve(const std::string& key, std::string value) const {
  state_->resolved[child_path(key)] = std::move(value);
}

namespace {
// A required key is absent. If the section holds a key the program never asked for that is a
// near miss of it, the message points at that line: the usual cause is a typo.
[[noreturn]] void missing(const State& s, const std::string& section_path, const YAML::Node& section,
                          const std::string& key, const std::string& what) {
  auto asked = s.requested.find(section_path);
  std::vector<std::string> unknown;
  std::map<std::string, YAML::Mark> marks;
  for (const auto& kv : section) {
    const std::string k = kv.first.Scalar();
    if (asked == s.requested.end() || !asked->second.count(k)) {
      unknown.push_back(k);
      marks[k] = kv.first.Mark();
    }
  }
  if (auto typo = closest_match(key, unknown)) {
    const std::string p = join_path(section_path, *typo);
    throw InputError(fmt::format("{}: unknown key '{}'; did you mean '{}'? (it is required: {})",
                                 location(s, p, marks[*typo]), p, key, what));
  }
  const std::string where = section_path.empty() ? s.source : location(s, section_path, section.Mark());
  throw InputError(fmt::format("{}: missing required key '{}' ({})", where, join_path(section_path, key), what));
}
}  // namespace

Section Section::section(const std::string& key) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) missing(*state_, path_, *node_, key, "a section of keys");
  if (!n.IsMap()) reject(key, "expected a section (indented key: value lines)");
  return Section(state_, std::make_shared<YAML::Node>(n), child_path(key));
}

Section Section::section_or_empty(const std::string& key) const {
  if (!has(key)) store_default(key, YAML::Node(YAML::NodeType::Map));
  return section(key);
}

std::optional<Section> Section::optional_section(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return section(key);
}

std::vector<Section> Section::sections(const std::string& key) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) missing(*state_, path_, *node_, key, "a list of sections");
  if (!n.IsSequence()) reject(key, "expected a list of sections ('- key: value' entries)");
  std::vector<Section> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", child_path(key), i);
    if (!n[i].IsMap())
      throw InputError(fmt::format("{}: entry '{}' must be a section of keys", location(*state_, p, n[i].Mark()), p));
    out.push_back(Section(state_, std::make_shared<YAML::Node>(n[i]), p));
  }
  return out;
}

template <class T>
T Section::convert(const std::string& key, const YAML::Node& n) const {
  if constexpr (std::is_same_v<T, double>) {
    double v = 0;
    std::size_t used = 0;
    const std::string text = n.IsScalar() ? n.Scalar() : "";
    if (!n.IsScalar() || !parse_double(text, v, used) || used != text.size()) reject(key, "expected a number");
    if (!std::isfinite(v)) reject(key, "expected a finite number");
    return v;
  } else if constexpr (std::is_same_v<T, long long> || std::is_same_v<T, int>) {
    T v = 0;
    const std::string text = n.IsScalar() ? n.Scalar() : "";
    auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (!n.IsScalar() || ec != std::errc() || p != text.data() + text.size()) reject(key, "expected a whole number");
    return v;
  } else if constexpr (std::is_same_v<T, bool>) {
    bool v = false;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v)) reject(key, "expected true or false");
    return v;
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!n.IsScalar()) reject(key, "expected a single value (text)");
    return n.Scalar();
  } else {
    using E = typename T::value_type;
    if (!n.IsSequence()) reject(key, "expected a list, e.g. [1, 2, 3]");
    T out;
    for (std::size_t i = 0; i < n.size(); ++i) {
      try {
        out.push_back(convert<E>(key, n[i]));
      } catch (const InputError&) {
        reject(key, fmt::format("entry {} ('{}') has the wrong type", i, one_line(n[i])));
      }
    }
    return out;
  }
}

template <class T>
T Section::get(const std::string& key) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) missing(*state_, path_, *node_, key, "a value");
  T v = convert<T>(key, n);
  resolve(key, resolved_text(v));
  return v;
}

template <class T>
T Section::get(const std::string& key, const T& fallback) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) {
    store_default(key, YAML::Node(fallback));
    resolve(key, resolved_text(fallback));
    return fallback;
  }
  T v = convert<T>(key, n);
  resolve(key, resolved_text(v));
  return v;
}

#define SUITE_CONFIG_INSTANTIATE(T)                     \
  template T Section::get<T>(const std::string&) const; \
  template T Section::get<T>(const std::string&, const T&) const;
SUITE_CONFIG_INSTANTIATE(bool)
SUITE_CONFIG_INSTANTIATE(int)
SUITE_CONFIG_INSTANTIATE(long long)
SUITE_CONFIG_INSTANTIATE(double)
SUITE_CONFIG_INSTANTIATE(std::string)
SUITE_CONFIG_INSTANTIATE(std::vector<double>)
SUITE_CONFIG_INSTANTIATE(std::vector<long long>)
SUITE_CONFIG_INSTANTIATE(std::vector<std::string>)
#undef SUITE_CONFIG_INSTANTIATE

double Section::number(const std::string& key, Range range) const {
  const double v = get<double>(key);
  if (!range.contains(v)) reject(key, "must be " + range.describe());
  return v;
}

double Section::number(const std::string& key, double fallback, Range range) const {
  const double v = get<double>(key, fallback);
  if (!range.contains(v)) reject(key, "must be " + range.describe());
  return v;
}

long long Section::integer(const std::string& key, long long fallback, long long min, long long max) const {
  const long long v = get<long long>(key, fallback);
  if (v < min || v > max) reject(key, fmt::format("must be a whole number in [{}, {}]", min, max));
  return v;
}

double Section::parse_quantity(const std::string& key, const YAML::Node& n, const std::string& unit) const {
  const std::string unit_note =
      unit.empty() || unit == "1" ? "" : fmt::format(" (in {} or another unit of the same kind)", unit);
  if (!n.IsScalar()) reject(key, "expected a number" + unit_note);
  const std::string text = n.Scalar();
  double v = 0;
  std::size_t used = 0;
  if (!parse_double(text, v, used)) reject(key, "expected a number" + unit_note);
  if (!std::isfinite(v)) reject(key, "expected a finite number" + unit_note);
  const std::string given = trim(std::string_view(text).substr(used));
  if (given.empty()) return v;
  try {
    return units::convert(v, given, unit.empty() ? "1" : unit);
  } catch (const InputError& e) {
    reject(key, e.what());
  }
}

void Section::check_range(const std::string& key, const YAML::Node& n, double v, const std::string& unit,
                          const Range& range) const {
  if (range.contains(v)) return;
  std::string problem = fmt::format("must be {}{}", range.describe(), unit.empty() ? "" : " " + unit);
  double bare = 0;
  std::size_t used = 0;
  const std::string text = n.Scalar();
  // A number without its unit is read in the key's unit: say so, since '30' meant in degrees
  // reads as 30 rad.
  if (!unit.empty() && unit != "1" && parse_double(text, bare, used) && trim(std::string_view(text).substr(used)).empty())
    problem += fmt::format("; '{}' has no unit, so it was read in {}: write the unit after the number{}", text, unit,
                           unit == "rad" ? fmt::format(", e.g. '{} deg'", text) : "");
  reject(key, problem);
}

double Section::quantity(const std::string& key, const std::string& unit, Range range) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull())
    missing(*state_, path_, *node_, key, unit.empty() ? "a number" : "a value in " + unit);
  const double v = parse_quantity(key, n, unit);
  check_range(key, n, v, unit, range);
  resolve(key, exact(v, unit));
  return v;
}

double Section::quantity(const std::string& key, const std::string& unit, double fallback, Range range) const {
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) {
    store_default(
        key, unit.empty() || unit == "1" ? YAML::Node(fallback) : YAML::Node(fmt::format("{} {}", fallback, unit)));
    resolve(key, exact(fallback, unit));
    return fallback;
  }
  const double v = parse_quantity(key, n, unit);
  check_range(key, n, v, unit, range);
  resolve(key, exact(v, unit));
  return v;
}

std::vector<std::vector<double>> Section::table(const std::string& key, const std::vector<std::string>& units) const {
  const YAML::Node n = child(key);
  const std::string shape = fmt::format("a list of rows [{}]", join(units));
  if (!n.IsDefined() || n.IsNull()) missing(*state_, path_, *node_, key, shape);
  if (!n.IsSequence() || n.size() == 0) reject(key, "expected " + shape);
  std::vector<std::vector<double>> out;
  for (std::size_t r = 0; r < n.size(); ++r) {
    const YAML::Node row = n[r];
    if (!row.IsSequence() || row.size() != units.size())
      reject(key,
             fmt::format("row {} ('{}') must have {} entries [{}]", r + 1, one_line(row), units.size(), join(units)));
    std::vector<double> values;
    for (std::size_t c = 0; c < units.size(); ++c) {
      try {
        values.push_back(parse_quantity(key, row[c], units[c]));
      } catch (const InputError&) {
        reject(key,
               fmt::format("row {}, entry {} ('{}') is not a value in {}", r + 1, c + 1, one_line(row[c]), units[c]));
      }
    }
    out.push_back(std::move(values));
  }
  std::string text;
  for (const auto& row : out) {
    std::string r;
    for (std::size_t c = 0; c < row.size(); ++c) r += (c ? ", " : "") + exact(row[c], units[c]);
    text += (text.empty() ? "[" : ", ") + ("[" + r + "]");
  }
  resolve(key, text + "]");
  return out;
}

std::string Section::choice(const std::string& key, const std::vector<std::string>& valid) const {
  const std::string v = get<std::string>(key);
  if (std::find(valid.begin(), valid.end(), v) != valid.end()) return v;
  std::string problem = fmt::format("must be one of {}", join(valid));
  if (auto best = closest_match(v, valid)) problem = fmt::format("did you mean '{}'? It {}", *best, problem);
  reject(key, problem);
}

std::string Section::choice(const std::string& key, const std::vector<std::string>& valid,
                            const std::string& fallback) const {
  if (!has(key)) {
    store_default(key, YAML::Node(fallback));
    resolve(key, fallback);
    return fallback;
  }
  return choice(key, valid);
}

std::filesystem::path Section::file(const std::string& key) const {
  const std::string name = get<std::string>(key);
  std::filesystem::path p(name);
  if (p.is_relative()) p = state_->base_dir / p;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec))
    reject(key, fmt::format("no such file ('{}'; a relative path is read from the scene file's folder)", p.string()));
  // The effective configuration names the file absolutely, so it can be rerun from anywhere.
  p = std::filesystem::absolute(p).lexically_normal();
  store_default(key, YAML::Node(p.string()));
  resolve(key, content_digest(p));
  return p;
}

std::vector<std::filesystem::path> Section::files(const std::string& key) const {
  std::vector<std::filesystem::path> out;
  for (const auto& name : get<std::vector<std::string>>(key)) {
    std::filesystem::path p(name);
    if (p.is_relative()) p = state_->base_dir / p;
    std::error_code ec;
    if (!std::filesystem::exists(p, ec))
      reject(key, fmt::format("no such file '{}' (a relative path is read from the scene file's folder)", p.string()));
    out.push_back(std::filesystem::absolute(p).lexically_normal());
  }
  YAML::Node list(YAML::NodeType::Sequence);
  std::string digests;
  for (const auto& p : out) {
    list.push_back(p.string());
    std::error_code ec;
    digests +=
        (digests.empty() ? "" : "; ") + (std::filesystem::is_regular_file(p, ec) ? content_digest(p) : "a folder");
  }
  store_default(key, list);
  resolve(key, "[" + digests + "]");
  return out;
}

void Section::record(const std::string& key, const std::vector<std::string>& values) const {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const auto& v : values) list.push_back(v);
  store_default(key, list);
}

const std::filesystem::path& Section::base_dir() const {
  return state_->base_dir;
}

YAML::Node Section::raw(const std::string& key) const {
  state_->free_form.insert(child_path(key));
  const YAML::Node n = child(key);
  if (n.IsDefined() && !n.IsNull()) resolve(key, one_line(n));
  return n;
}

// --------------------------------------------------------------------------------------- Config

Config Config::from_string(const std::string& text, const std::string& source_name,
                           const std::vector<std::string>& overrides, const std::string& override_origin) {
  return Config(load(text, source_name, overrides, override_origin));
}

Config Config::from_file(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                         const std::string& override_origin) {
  std::ifstream in(path);
  if (!in) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(path, ec);
    throw InputError(fmt::format("cannot open configuration file '{}': {}", path.string(),
                                 exists ? "it is not readable" : "no such file"));
  }
  std::stringstream text;
  text << in.rdbuf();
  auto state = load(text.str(), path.string(), overrides, override_origin);
  state->base_dir = path.parent_path();
  return Config(std::move(state));
}

Section Config::root() const {
  return Section(state_, std::make_shared<YAML::Node>(state_->root), "");
}

void Config::finish() const {
  check_known(*state_, state_->root, "");
}

std::string Config::effective_yaml() const {
  YAML::Emitter out;
  out << YAML::Comment(fmt::format("effective configuration: {} + command-line overrides + defaults", state_->source))
      << YAML::Newline << state_->root;
  return std::string(out.c_str()) + "\n";
}

void Config::write_effective(const std::filesystem::path& path) const {
  io::write_file_atomic(path, effective_yaml());
}

const std::map<std::string, std::string>& Config::resolved() const {
  return state_->resolved;
}

const std::string& Config::source_name() const {
  return state_->source;
}

bool looks_like_override(const std::string& arg) {
  const auto eq = arg.find('=');
  return eq != std::string::npos && eq > 0 && arg[0] != '-';
}

}  // namespace suite::config
