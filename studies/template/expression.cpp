#include "studies/template/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <numbers>

#include "core/config/suggest.hpp"

namespace suite::studies {

namespace {

// ---- Python's arithmetic, for the operators and functions muParser lacks or spells differently

// CPython's float floor division (float_floor_div): exact for integers, floors towards -inf.
double py_floor_div(double a, double b) {
  if (b == 0.0) return a / b;  // Python raises ZeroDivisionError; we give IEEE's inf or nan
  const double mod = std::fmod(a, b);
  double div = (a - mod) / b;
  if (mod != 0.0 && (b < 0) != (mod < 0)) div -= 1.0;
  if (div == 0.0) return std::copysign(0.0, a / b);
  double floor_div = std::floor(div);
  if (div - floor_div > 0.5) floor_div += 1.0;
  return floor_div;
}

// CPython's float modulo (float_rem): the result takes the sign of the divisor.
double py_mod(double a, double b) {
  double mod = std::fmod(a, b);
  if (mod == 0.0) return std::copysign(0.0, b);
  if ((b < 0) != (mod < 0)) mod += b;
  return mod;
}

// Python's min and max keep the first of equal values and compare with < and >.
double py_min(const double* v, int n) {
  double m = v[0];
  for (int i = 1; i < n; ++i)
    if (v[i] < m) m = v[i];
  return m;
}

double py_max(const double* v, int n) {
  double m = v[0];
  for (int i = 1; i < n; ++i)
    if (v[i] > m) m = v[i];
  return m;
}

// The functions an expression may call, with their number of arguments (-1: any number).
// In the translation each is called "py_<name>"; log with a base becomes "py_log_base".
struct Function {
  const char* name;
  int min_args, max_args;
};

constexpr Function kFunctions[] = {
    {"abs", 1, 1}, {"acos", 1, 1},  {"asin", 1, 1}, {"atan", 1, 1},  {"ceil", 1, 1}, {"cos", 1, 1},  {"cosh", 1, 1},
    {"exp", 1, 1}, {"floor", 1, 1}, {"log", 1, 2},  {"log10", 1, 1}, {"max", 2, -1}, {"min", 2, -1}, {"pow", 2, 2},
    {"sin", 1, 1}, {"sinh", 1, 1},  {"sqrt", 1, 1}, {"tan", 1, 1},   {"tanh", 1, 1},
};

// The C library's functions, which are also what Python's math module calls.
void define_functions(mu::Parser& p) {
  using Unary = double (*)(double);
  using Binary = double (*)(double, double);
  p.DefineFun("py_abs", Unary{[](double x) { return std::fabs(x); }});
  p.DefineFun("py_acos", Unary{[](double x) { return std::acos(x); }});
  p.DefineFun("py_asin", Unary{[](double x) { return std::asin(x); }});
  p.DefineFun("py_atan", Unary{[](double x) { return std::atan(x); }});
  p.DefineFun("py_ceil", Unary{[](double x) { return std::ceil(x); }});
  p.DefineFun("py_cos", Unary{[](double x) { return std::cos(x); }});
  p.DefineFun("py_cosh", Unary{[](double x) { return std::cosh(x); }});
  p.DefineFun("py_exp", Unary{[](double x) { return std::exp(x); }});
  p.DefineFun("py_floor", Unary{[](double x) { return std::floor(x); }});
  p.DefineFun("py_log", Unary{[](double x) { return std::log(x); }});
  p.DefineFun("py_log_base", Binary{[](double x, double base) { return std::log(x) / std::log(base); }});
  p.DefineFun("py_log10", Unary{[](double x) { return std::log10(x); }});
  p.DefineFun("py_max", py_max);
  p.DefineFun("py_min", py_min);
  p.DefineFun("py_pow", Binary{[](double x, double y) { return std::pow(x, y); }});
  p.DefineFun("py_sin", Unary{[](double x) { return std::sin(x); }});
  p.DefineFun("py_sinh", Unary{[](double x) { return std::sinh(x); }});
  p.DefineFun("py_sqrt", Unary{[](double x) { return std::sqrt(x); }});
  p.DefineFun("py_tan", Unary{[](double x) { return std::tan(x); }});
  p.DefineFun("py_tanh", Unary{[](double x) { return std::tanh(x); }});
  p.DefineFun("py_floor_div", py_floor_div);
  p.DefineFun("py_mod", py_mod);
}

// ---- Reading the text

struct Token {
  enum Kind { kNumber, kName, kOperator, kEnd } kind;
  std::string text;
  std::size_t pos;  // 0-based offset in the expression
  double value = 0.0;
};

bool is_name_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// A Python float literal at `pos`: digits, an optional fraction, an optional exponent.
Token read_number(const std::string& s, std::size_t pos) {
  std::size_t i = pos;
  while (i < s.size() && is_digit(s[i])) ++i;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i;
  }
  bool bad = false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    bad = j >= s.size() || !is_digit(s[j]);
    while (j < s.size() && is_digit(s[j])) ++j;
    i = j;
  }
  std::size_t end = i;
  while (end < s.size() && (is_name_char(s[end]) || s[end] == '.')) ++end;
  const std::string text = s.substr(pos, end - pos);
  if (bad || end != i) {
    const bool letter_follows = end != i && is_name_start(s[i]);
    throw ExpressionError(
        s, pos, fmt::format("invalid number '{}'{}", text, letter_follows ? " (write 2*x, not 2x, to multiply)" : ""));
  }
  Token t{Token::kNumber, text, pos};
  const auto r = std::from_chars(text.data(), text.data() + text.size(), t.value);
  if (r.ec != std::errc()) t.value = std::strtod(text.c_str(), nullptr);  // out of range: inf or 0, as Python
  return t;
}

// Splits an expression into tokens; ExpressionError for anything Python would not accept.
std::vector<Token> tokenize(const std::string& s) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (is_digit(c) || (c == '.' && i + 1 < s.size() && is_digit(s[i + 1]))) {
      tokens.push_back(read_number(s, i));
      i += tokens.back().text.size();
    } else if (is_name_start(c)) {
      std::size_t j = i;
      while (j < s.size() && is_name_char(s[j])) ++j;
      tokens.push_back({Token::kName, s.substr(i, j - i), i});
      i = j;
    } else if ((c == '*' || c == '/') && i + 1 < s.size() && s[i + 1] == c) {
      tokens.push_back({Token::kOperator, s.substr(i, 2), i});
      i += 2;
    } else if (std::string_view("+-*/%(),").find(c) != std::string_view::npos) {
      tokens.push_back({Token::kOperator, std::string(1, c), i});
      ++i;
    } else if (c == '^') {
      throw ExpressionError(s, i, "'^' is not a power operator here; write ** (2**3 = 8)");
    } else if (std::isprint(static_cast<unsigned char>(c))) {
      throw ExpressionError(s, i, fmt::format("unexpected character '{}'", c));
    } else {
      throw ExpressionError(s, i, fmt::format("unexpected byte 0x{:02x}", static_cast<unsigned char>(c)));
    }
  }
  tokens.push_back({Token::kEnd, "", s.size()});
  return tokens;
}

std::string describe(const Token& t) {
  switch (t.kind) {
    case Token::kNumber:
      return fmt::format("number '{}'", t.text);
    case Token::kName:
      return fmt::format("name '{}'", t.text);
    case Token::kOperator:
      return fmt::format("'{}'", t.text);
    case Token::kEnd:
      break;
  }
  return "end of expression";
}

// A variable as the expression first uses it.
struct Use {
  std::string name;
  std::size_t pos;
};

// Recursive descent over Python's grammar of arithmetic:
//   sum     = term (('+' | '-') term)*
//   term    = factor (('*' | '/' | '//' | '%') factor)*
//   factor  = ('+' | '-') factor | power
//   power   = primary ['**' factor]
//   primary = number | name | name '(' sum (',' sum)* ')' | '(' sum ')'
// It writes the muParser translation with every operation in parentheses; numbers become the
// constants py_k<i> and variables py_v<i> (so no name can clash with one of muParser's).
class Translator {
 public:
  explicit Translator(const std::string& text) : text_(text), tokens_(tokenize(text)) {}

  std::string run() {
    if (peek().kind == Token::kEnd) fail(peek(), "empty expression");
    std::string out = sum();
    if (peek().kind != Token::kEnd) fail(peek(), "unexpected " + describe(peek()));
    return out;
  }

  std::vector<Use> uses;         // variables in order of first use
  std::vector<double> literals;  // the numbers, in order

 private:
  static constexpr int kMaxDepth = 100;  // Python's parser gives up at about 200

  const Token& peek() const { return tokens_[next_]; }
  const Token& take() { return tokens_[next_++]; }
  bool at(const char* op) const { return peek().kind == Token::kOperator && peek().text == op; }
  [[noreturn]] void fail(const Token& t, const std::string& problem) const {
    throw ExpressionError(text_, t.pos, problem);
  }
  void deeper(const Token& t) {
    if (++depth_ > kMaxDepth) fail(t, "expression nested too deeply");
  }

  std::string sum() {
    std::string out = term();
    while (at("+") || at("-")) {
      const std::string op = take().text;
      out = "(" + out + op + term() + ")";
    }
    return out;
  }

  std::string term() {
    std::string out = factor();
    while (at("*") || at("/") || at("//") || at("%")) {
      const std::string op = take().text;
      const std::string rhs = factor();
      if (op == "//") {
        out = "py_floor_div(" + out + "," + rhs + ")";
      } else if (op == "%") {
        out = "py_mod(" + out + "," + rhs + ")";
      } else {
        out = "(" + out + op + rhs + ")";
      }
    }
    return out;
  }

  std::string factor() {
    if (at("+") || at("-")) {
      const Token& sign = take();
      deeper(sign);
      std::string operand = factor();
      --depth_;
      return sign.text == "-" ? "(-" + operand + ")" : operand;
    }
    return power();
  }

  std::string power() {
    std::string base = primary();
    if (!at("**")) return base;
    const Token& op = take();
    deeper(op);
    std::string exponent = factor();  // a factor: right-associative, and 2**-1 is allowed
    --depth_;
    return "(" + base + "^" + exponent + ")";
  }

  std::string primary() {
    const Token& t = take();
    if (t.kind == Token::kNumber) {
      literals.push_back(t.value);
      return fmt::format("py_k{}", literals.size() - 1);
    }
    if (t.kind == Token::kName) return at("(") ? call(t) : variable(t);
    if (t.kind == Token::kOperator && t.text == "(") {
      deeper(t);
      std::string inner = sum();
      --depth_;
      close(t);
      return "(" + inner + ")";
    }
    fail(t, "unexpected " + describe(t));
  }

  void close(const Token& open) {
    if (at(")")) {
      take();
      return;
    }
    if (peek().kind == Token::kEnd) fail(open, "'(' is never closed");
    fail(peek(),
         fmt::format("unexpected {}; expected ')' to close '(' at character {}", describe(peek()), open.pos + 1));
  }

  std::string variable(const Token& t) {
    auto it = std::find_if(uses.begin(), uses.end(), [&](const Use& u) { return u.name == t.text; });
    if (it == uses.end()) it = uses.insert(uses.end(), Use{t.text, t.pos});
    return fmt::format("py_v{}", it - uses.begin());
  }

  std::string call(const Token& name) {
    const auto* f = std::find_if(std::begin(kFunctions), std::end(kFunctions),
                                 [&](const Function& g) { return name.text == g.name; });
    if (f == std::end(kFunctions)) {
      std::vector<std::string> known;
      for (const auto& g : kFunctions) known.emplace_back(g.name);
      const auto guess = closest_match(name.text, known);
      fail(name, fmt::format("unknown function '{}'{}; known functions: {}", name.text,
                             guess ? " (did you mean '" + *guess + "'?)" : "", join(known)));
    }
    const Token& open = take();
    deeper(open);
    std::vector<std::string> args{sum()};
    while (at(",")) {
      take();
      args.push_back(sum());
    }
    --depth_;
    close(open);
    const int n = static_cast<int>(args.size());
    if (n < f->min_args || (f->max_args >= 0 && n > f->max_args)) {
      const std::string wanted = f->max_args < 0              ? fmt::format("at least {}", f->min_args)
                                 : f->min_args == f->max_args ? fmt::format("{}", f->min_args)
                                                              : fmt::format("{} or {}", f->min_args, f->max_args);
      fail(name, fmt::format("{}() takes {} argument{}, not {}", f->name, wanted, wanted == "1" ? "" : "s", n));
    }
    const std::string callee = name.text == "log" && n == 2 ? "py_log_base" : "py_" + name.text;
    return callee + "(" + join(args, ",") + ")";
  }

  const std::string& text_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  int depth_ = 0;
};

std::string unknown_variable(const std::string& name, const std::map<std::string, double>& variables) {
  if (variables.empty()) return fmt::format("unknown variable '{}'; no variables are defined", name);
  std::vector<std::string> valid;
  for (const auto& [key, value] : variables) valid.push_back(key);
  const auto guess = closest_match(name, valid);
  return fmt::format("unknown variable '{}'{}; valid names: {}", name, guess ? " (did you mean '" + *guess + "'?)" : "",
                     join(valid));
}

}  // namespace

ExpressionError::ExpressionError(const std::string& expression, std::size_t position, const std::string& problem)
    : InputError(fmt::format("expression \"{}\", character {}: {}", expression, position + 1, problem)),
      position_(position),
      problem_(problem) {}

struct Expression::Impl {
  std::string text;
  std::vector<std::string> names;      // sorted, without the constants
  std::vector<Use> uses;               // one muParser variable per use, in this order
  std::mutex mutex;                    // evaluate() writes `slots`, then runs `parser`
  std::vector<double> slots;           // muParser reads the variables from here; never resized
  std::unique_ptr<mu::Parser> parser;  // null when the expression is a bare name
};

Expression::Expression(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Expression::Expression(const Expression& other)
    : impl_(other.impl_ ? compile(other.impl_->text).impl_.release() : nullptr) {}
Expression& Expression::operator=(const Expression& other) {
  if (this != &other) *this = Expression(other);
  return *this;
}
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;
Expression::~Expression() = default;

const std::string& Expression::text() const {
  return impl_->text;
}
const std::vector<std::string>& Expression::names() const {
  return impl_->names;
}

Expression Expression::compile(const std::string& text) {
  auto impl = std::make_unique<Impl>();
  impl->text = text;
  Translator translator(text);
  const std::string translation = translator.run();
  impl->uses = std::move(translator.uses);
  for (const auto& use : impl->uses) {
    if (use.name != "pi" && use.name != "e") impl->names.push_back(use.name);
  }
  std::sort(impl->names.begin(), impl->names.end());
  impl->slots.assign(impl->uses.size(), 1.0);
  if (translation == "py_v0") return Expression(std::move(impl));  // a bare name needs no parser
  try {
    auto parser = std::make_unique<mu::Parser>();
    parser->EnableOptimizer(false);  // its rewrites (x*a+b) would change the rounding
    define_functions(*parser);
    for (std::size_t i = 0; i < translator.literals.size(); ++i) {
      parser->DefineConst(fmt::format("py_k{}", i), translator.literals[i]);
    }
    for (std::size_t i = 0; i < impl->slots.size(); ++i) {
      parser->DefineVar(fmt::format("py_v{}", i), &impl->slots[i]);
    }
    parser->SetExpr(translation);
    parser->Eval();  // muParser compiles on the first call; later calls run the byte code
    impl->parser = std::move(parser);
  } catch (const mu::Parser::exception_type& e) {
    throw ExpressionError(text, 0, "muParser rejected its translation '" + translation + "': " + e.GetMsg());
  }
  return Expression(std::move(impl));
}

double Expression::evaluate(const std::map<std::string, double>& variables) const {
  std::lock_guard lock(impl_->mutex);
  for (std::size_t i = 0; i < impl_->uses.size(); ++i) {
    const Use& use = impl_->uses[i];
    const auto it = variables.find(use.name);
    if (it != variables.end()) {
      impl_->slots[i] = it->second;
    } else if (use.name == "pi") {
      impl_->slots[i] = std::numbers::pi;
    } else if (use.name == "e") {
      impl_->slots[i] = std::numbers::e;
    } else {
      throw ExpressionError(impl_->text, use.pos, unknown_variable(use.name, variables));
    }
  }
  if (!impl_->parser) return impl_->slots[0];
  try {
    return impl_->parser->Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw ExpressionError(impl_->text, 0, "muParser: " + e.GetMsg());
  }
}

double evaluate_expression(const std::string& text, const std::map<std::string, double>& variables) {
  return Expression::compile(text).evaluate(variables);
}

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

}  // namespace suite::studies
