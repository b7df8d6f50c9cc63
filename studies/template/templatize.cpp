#include "studies/template/templatize.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <regex>

#include "core/errors.hpp"

namespace suite::studies {

namespace {

struct Edit {
  std::size_t at = 0, length = 0;
  std::string name;
};

// Offset of the first character of line `line` (1-based), or npos.
std::size_t line_start(const std::string& text, long line) {
  std::size_t at = 0;
  for (long l = 1; l < line; ++l) {
    at = text.find('\n', at);
    if (at == std::string::npos) return at;
    ++at;
  }
  return at <= text.size() ? at : std::string::npos;
}

// The length of the number starting at `at` (0 if none), and its value.
std::size_t number_at(const std::string& text, std::size_t at, double& value) {
  const char* begin = text.c_str() + at;
  char* end = nullptr;
  value = std::strtod(begin, &end);
  const auto n = static_cast<std::size_t>(end - begin);
  return n > 0 && std::isfinite(value) ? n : 0;
}

Edit field_location(const std::string& text, const std::string& source, const std::string& name, long line, long field,
                    double& value) {
  const std::size_t start = line_start(text, line);
  if (start == std::string::npos)
    throw InputError(fmt::format("{}: variable {}: there is no line {}", source, name, line));
  const std::size_t end = std::min(text.find('\n', start), text.size());
  std::size_t at = start;
  for (long f = 1;; ++f) {
    while (at < end && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    if (at >= end)
      throw InputError(fmt::format("{}:{}: variable {}: the line has fewer than {} fields", source, line, name, field));
    std::size_t stop = at;
    while (stop < end && !std::isspace(static_cast<unsigned char>(text[stop]))) ++stop;
    if (f == field) {
      const std::size_t n = number_at(text, at, value);
      if (n != stop - at)
        throw InputError(fmt::format("{}:{}: variable {}: field {} is '{}', not a number", source, line, name, field,
                                     text.substr(at, stop - at)));
      return {at, n, name};
    }
    at = stop;
  }
}

Edit key_location(const std::string& text, const std::string& source, const std::string& name, const std::string& path,
                  double& value) {
  YAML::Node node;
  try {
    node = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(
        fmt::format("{}: variable {} names a key ('{}') but the file is not YAML: {}", source, name, path, e.msg));
  }
  static const std::regex part(R"(([^.\[\]]+)(?:\[(\d+)\])?)");
  std::string walked;
  std::size_t from = 0;
  while (from < path.size()) {
    const std::size_t dot = path.find('.', from);
    const std::string piece = path.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
    std::smatch m;
    if (!std::regex_match(piece, m, part))
      throw InputError(fmt::format("variable {}: '{}' is not a key path (key.key or key[index])", name, path));
    if (!walked.empty()) walked += '.';
    walked += m[1].str();
    if (!node.IsMap() || !node[m[1].str()])
      throw InputError(fmt::format("{}: variable {}: there is no key '{}'", source, name, walked));
    node.reset(node[m[1].str()]);
    if (m[2].matched) {
      const auto i = std::stoul(m[2].str());
      if (!node.IsSequence() || i >= node.size())
        throw InputError(fmt::format("{}: variable {}: '{}' has no item {}", source, name, walked, i));
      node.reset(node[i]);
    }
    if (dot == std::string::npos) break;
    from = dot + 1;
  }
  const auto mark = node.Mark();
  if (!node.IsScalar() || mark.pos < 0)
    throw InputError(fmt::format("{}: variable {}: '{}' is not a single value", source, name, path));
  const auto at = static_cast<std::size_t>(mark.pos);
  const std::size_t n = number_at(text, at, value);
  if (n == 0)
    throw InputError(fmt::format("{}:{}:{}: variable {}: '{}' does not start with a number", source, mark.line + 1,
                                 mark.column + 1, name, node.as<std::string>()));
  return {at, n, name};
}

}  // namespace

Templatized templatize(const std::string& text, const std::string& source,
                       const std::vector<std::pair<std::string, std::string>>& variables) {
  static const std::regex line_field(R"((\d+):(\d+))");
  Templatized out;
  std::vector<Edit> edits;
  for (const auto& [name, location] : variables) {
    double value = 0.0;
    std::smatch m;
    edits.push_back(std::regex_match(location, m, line_field)
                        ? field_location(text, source, name, std::stol(m[1].str()), std::stol(m[2].str()), value)
                        : key_location(text, source, name, location, value));
    if (!out.values.emplace(name, value).second) throw InputError(fmt::format("variable {} is given twice", name));
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.at < b.at; });
  for (std::size_t i = 1; i < edits.size(); ++i)
    if (edits[i].at < edits[i - 1].at + edits[i - 1].length)
      throw InputError(
          fmt::format("{}: variables {} and {} name the same number", source, edits[i - 1].name, edits[i].name));
  std::size_t next = 0;
  for (std::size_t at = 0; at < text.size();) {
    if (next < edits.size() && at == edits[next].at) {
      out.text += '{';
      out.text += edits[next].name;
      out.text += '}';
      at += edits[next].length;
      ++next;
      continue;
    }
    if (text[at] == '{' || text[at] == '}') out.text += '\\';
    out.text += text[at++];
  }
  return out;
}

}  // namespace suite::studies
