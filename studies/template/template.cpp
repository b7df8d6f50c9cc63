#include "studies/template/template.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/errors.hpp"

namespace suite::studies {

namespace {

// "file:line:column" for messages.
// "kd = 3, su = 5": the variables an evaluation rendered with.
std::string describe(const std::map<std::string, double>& values) {
  std::string text;
  for (const auto& [name, v] : values) text += (text.empty() ? "" : ", ") + name + " = " + format_number(v);
  return text;
}

std::string place(const std::string& source, std::size_t line, std::size_t column) {
  return fmt::format("{}:{}:{}", source, line, column);
}

}  // namespace

Template Template::parse(const std::string& text, const std::string& source_name) {
  Template t;
  t.source_name_ = source_name;
  std::string literal;
  std::size_t line = 1, line_start = 0;
  const auto flush_literal = [&] {
    if (literal.empty()) return;
    t.literal_size_ += literal.size();
    t.pieces_.push_back(Piece{std::move(literal), std::nullopt});
    literal.clear();
  };

  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    const std::size_t column = i - line_start + 1;
    if (c == '\\' && i + 1 < text.size() && (text[i + 1] == '{' || text[i + 1] == '}')) {
      literal += text[i + 1];
      i += 2;
    } else if (c == '}') {
      throw InputError(place(source_name, line, column) + ": unmatched '}' (write \\} for a literal brace)");
    } else if (c == '{') {
      const std::size_t end = text.find_first_of("{}\n", i + 1);
      if (end == std::string::npos || text[end] != '}') {
        const std::string why = end == std::string::npos ? "no '}' follows"
                                : text[end] == '\n'
                                    ? "no '}' before the end of the line"
                                    : fmt::format("another '{{' at column {} comes first", end - line_start + 1);
        throw InputError(place(source_name, line, column) + ": unmatched '{' (" + why +
                         "; write \\{ for a literal brace)");
      }
      const std::string content = text.substr(i + 1, end - i - 1);
      flush_literal();
      try {
        t.pieces_.push_back(Piece{"", Expression::compile(content), line, column + 1});
      } catch (const ExpressionError& e) {
        throw InputError(fmt::format("{}: in {{{}}}: {}", place(source_name, line, column + 1 + e.position()), content,
                                     e.problem()));
      }
      const auto& used = t.pieces_.back().tag->names();
      t.names_.insert(t.names_.end(), used.begin(), used.end());
      i = end + 1;
    } else {
      literal += c;
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
    }
  }
  flush_literal();
  std::sort(t.names_.begin(), t.names_.end());
  t.names_.erase(std::unique(t.names_.begin(), t.names_.end()), t.names_.end());
  return t;
}

std::string Template::render(const std::map<std::string, double>& values) const {
  std::string out;
  out.reserve(literal_size_ + 16 * pieces_.size());
  for (const Piece& piece : pieces_) {
    if (!piece.tag) {
      out += piece.literal;
      continue;
    }
    double value = 0;
    try {
      value = piece.tag->evaluate(values);
    } catch (const ExpressionError& e) {
      throw InputError(fmt::format("{}: in {{{}}}: {}", place(source_name_, piece.line, piece.column + e.position()),
                                   piece.tag->text(), e.problem()));
    }
    // Where Python raises (a division by zero, a negative number to a fractional power, an
    // overflow) the expression gives inf or nan: never a value for an input file.
    if (!std::isfinite(value))
      throw InputError(
          fmt::format("{}: {{{}}} gives {} at {}: Python raises here (a division by zero, a negative "
                      "number to a fractional power or an overflow); a template value must be a finite "
                      "number",
                      place(source_name_, piece.line, piece.column), piece.tag->text(),
                      std::isnan(value) ? std::string("nan") : format_number(value), describe(values)));
    out += format_number(value);
  }
  return out;
}

}  // namespace suite::studies
