#pragma once
// Input-file templates (docs/methods/studies.md, "Templates"):
//
//   IEMODEL 2 120 {Kd} {Us} 0.2
//   0 {4*(2**Scale)}
//
// `{name}` is replaced by the variable's value and `{expression}` by the value of a Python-like
// expression (expression.hpp), both printed with format_number ("%.10g"). `\{` and `\}` stand
// for literal braces; any other backslash is copied as it is. Everything outside the braces is
// copied byte for byte, so fixed-column input files keep their spacing. A tag ends at the first
// '}' and may not span lines.
//
// The text is parsed once (expressions compiled once); render() then only evaluates, so
// thousands of renders per second are cheap. Not collective.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "studies/template/expression.hpp"

namespace suite::studies {

class Template {
 public:
  // InputError naming source_name:line:column for an unmatched brace or a bad expression.
  static Template parse(const std::string& text, const std::string& source_name);

  // The filled-in text. InputError naming source_name:line:column, the missing variable and
  // the names `values` does hold.
  std::string render(const std::map<std::string, double>& values) const;

  // The variables the template uses, sorted and unique (pi and e only count as variables when
  // `values` defines them, so they are not listed).
  std::vector<std::string> names() const { return names_; }

  const std::string& source_name() const { return source_name_; }

 private:
  // Literal text, or a tag with its compiled expression and place in the source.
  struct Piece {
    std::string literal;
    std::optional<Expression> tag;     // empty for literal text
    std::size_t line = 0, column = 0;  // 1-based, of the first character inside the braces
  };

  std::string source_name_;
  std::vector<Piece> pieces_;
  std::vector<std::string> names_;
  std::size_t literal_size_ = 0;  // for reserving the output
};

}  // namespace suite::studies
