#pragma once
// Arithmetic expressions with Python's syntax and semantics, evaluated by muParser
// (docs/methods/studies.md, "Templates").
//
//   + - * / // % **, parentheses, numbers such as 2, 2.5, .5, 1e-3
//   sin cos tan asin acos atan sinh cosh tanh exp log log10 sqrt abs floor ceil min max pow
//   constants pi and e (a variable of the same name takes their place, as in Python)
//
// Precedence and associativity are Python's: ** binds tighter than unary minus and groups to
// the right (-2**2 = -4, 2**3**2 = 512, 2**-1 = 0.5); // and % floor towards minus infinity and
// take the sign of the divisor. Our own parser reads the text (so errors name the character)
// and hands muParser a fully parenthesised translation, so muParser's own precedence never
// matters. Where Python would raise (division by zero, a negative base to a fractional power)
// the result is the IEEE value (inf, nan).
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace suite::studies {

// A mistake in an expression: bad syntax or a missing variable. what() is one line,
//   expression "2 +* 3", character 4: unexpected '*'
// position() is the 0-based byte offset of the offending character, so that templates can
// turn it into a line and column of their own file.
class ExpressionError : public InputError {
 public:
  ExpressionError(const std::string& expression, std::size_t position, const std::string& problem);
  std::size_t position() const { return position_; }
  const std::string& problem() const { return problem_; }  // what is wrong, without the place

 private:
  std::size_t position_;
  std::string problem_;
};

// An expression parsed once and evaluated many times. evaluate() is safe to call from several
// threads (a lock guards the muParser object); copying an Expression compiles it again.
class Expression {
 public:
  // ExpressionError for bad syntax, an unknown function or a wrong number of arguments.
  static Expression compile(const std::string& text);

  Expression(const Expression& other);
  Expression& operator=(const Expression& other);
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;
  ~Expression();

  const std::string& text() const;
  // The variables it needs, sorted and unique; pi and e are not listed (they are constants
  // unless `variables` gives them a value).
  const std::vector<std::string>& names() const;
  // ExpressionError naming the first missing variable and the valid names.
  double evaluate(const std::map<std::string, double>& variables) const;

 private:
  struct Impl;
  explicit Expression(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Compiles and evaluates `text` once (for repeated use, keep an Expression).
double evaluate_expression(const std::string& text, const std::map<std::string, double>& variables);

// printf's "%.10g": 32.0 -> "32", 0.1 + 0.2 -> "0.3", 1e-20 -> "1e-20".
std::string format_number(double v);

}  // namespace suite::studies
