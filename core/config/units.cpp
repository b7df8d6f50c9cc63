#include "core/config/units.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "core/errors.hpp"

namespace suite::units {
namespace {

constexpr std::array<int, 4> kLength{1, 0, 0, 0}, kMass{0, 1, 0, 0}, kTime{0, 0, 1, 0}, kAngle{0, 0, 0, 1},
    kNone{0, 0, 0, 0}, kForce{1, 1, -2, 0}, kPressure{-1, 1, -2, 0}, kVolume{3, 0, 0, 0}, kFlow{3, 0, -1, 0};

// Exact factors where a definition exists (international foot, avoirdupois pound, lbf = lb*g0).
const std::unordered_map<std::string_view, Unit>& symbols() {
  static const std::unordered_map<std::string_view, Unit> table = {
      {"m", {1.0, kLength}},
      {"cm", {1e-2, kLength}},
      {"mm", {1e-3, kLength}},
      {"um", {1e-6, kLength}},
      {"km", {1e3, kLength}},
      {"ft", {0.3048, kLength}},
      {"in", {0.0254, kLength}},
      {"yd", {0.9144, kLength}},
      {"mi", {1609.344, kLength}},
      {"kg", {1.0, kMass}},
      {"g", {1e-3, kMass}},
      {"mg", {1e-6, kMass}},
      {"t", {1e3, kMass}},
      {"lb", {0.45359237, kMass}},
      {"s", {1.0, kTime}},
      {"ms", {1e-3, kTime}},
      {"min", {60.0, kTime}},
      {"h", {3600.0, kTime}},
      {"hr", {3600.0, kTime}},
      {"day", {86400.0, kTime}},
      {"N", {1.0, kForce}},
      {"kN", {1e3, kForce}},
      {"lbf", {4.4482216152605, kForce}},
      {"Pa", {1.0, kPressure}},
      {"kPa", {1e3, kPressure}},
      {"MPa", {1e6, kPressure}},
      {"GPa", {1e9, kPressure}},
      {"psf", {47.88025898033584, kPressure}},
      {"psi", {6894.757293168361, kPressure}},
      {"L", {1e-3, kVolume}},
      {"acre", {4046.8564224, {2, 0, 0, 0}}},
      {"cfs", {0.028316846592, kFlow}},
      {"rad", {1.0, kAngle}},
      {"deg", {std::numbers::pi / 180.0, kAngle}},
      {"1", {1.0, kNone}},
  };
  return table;
}

class Parser {
 public:
  explicit Parser(std::string_view s) : s_(s) {}

  Unit parse_all() {
    Unit u = expression();
    skip_space();
    if (pos_ != s_.size()) fail(fmt::format("unexpected '{}'", s_[pos_]));
    return u;
  }

 private:
  // expression := term ('/' term)*   (every term after a '/' divides)
  Unit expression() {
    Unit u = term();
    for (skip_space(); peek() == '/'; skip_space()) {
      ++pos_;
      combine(u, term(), -1);
    }
    return u;
  }
  // term := factor (('*' | '.' | ' ') factor)*
  Unit term() {
    Unit u = factor();
    while (true) {
      const std::size_t save = pos_;
      const bool had_space = skip_space();
      const char c = peek();
      if (c == '*' || c == '.') {
        ++pos_;
        skip_space();
      } else if (!(had_space && (std::isalpha(static_cast<unsigned char>(c)) || c == '('))) {
        pos_ = save;
        return u;
      }
      combine(u, factor(), +1);
    }
  }
  // factor := ('(' expression ')' | symbol) [ '^' ['-'] digits | digits ]
  Unit factor() {
    skip_space();
    Unit u;
    if (peek() == '(') {
      ++pos_;
      u = expression();
      skip_space();
      if (peek() != ')') fail("missing ')'");
      ++pos_;
    } else {
      const std::size_t start = pos_;
      while (pos_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
      if (start == pos_ && peek() == '1') ++pos_;  // "1/s"
      const std::string_view sym = s_.substr(start, pos_ - start);
      if (sym.empty()) fail("expected a unit symbol");
      auto it = symbols().find(sym);
      if (it == symbols().end()) fail(fmt::format("unknown unit symbol '{}'", sym));
      u = it->second;
    }
    int power = 1;
    if (peek() == '^') {
      ++pos_;
      power = integer();
    } else if (std::isdigit(static_cast<unsigned char>(peek()))) {
      power = integer();
    }
    Unit p;
    combine(p, u, power);
    return p;
  }
  int integer() {
    int sign = 1;
    if (peek() == '-') {
      sign = -1;
      ++pos_;
    }
    if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected an integer power");
    int v = 0;
    while (std::isdigit(static_cast<unsigned char>(peek()))) v = 10 * v + (s_[pos_++] - '0');
    return sign * v;
  }
  static void combine(Unit& into, const Unit& f, int power) {
    into.to_si *= std::pow(f.to_si, power);
    for (std::size_t i = 0; i < 4; ++i) into.dim[i] += power * f.dim[i];
  }
  bool skip_space() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] == ' ') ++pos_;
    return pos_ != start;
  }
  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("cannot read unit '{}': {} at character {}", s_, what, pos_ + 1));
  }

  std::string_view s_;
  std::size_t pos_ = 0;
};

}  // namespace

Unit parse(std::string_view text) {
  if (text.empty()) return Unit{};
  return Parser(text).parse_all();
}

std::string describe(const std::array<int, 4>& dim) {
  static constexpr const char* names[4] = {"length", "mass", "time", "angle"};
  std::string num, den;
  for (std::size_t i = 0; i < 4; ++i) {
    const int p = dim[i];
    if (p == 0) continue;
    std::string& side = p > 0 ? num : den;
    if (!side.empty()) side += "*";
    side += names[i];
    if (std::abs(p) != 1) side += fmt::format("^{}", std::abs(p));
  }
  if (num.empty() && den.empty()) return "dimensionless";
  return (num.empty() ? "1" : num) + (den.empty() ? "" : "/" + den);
}

double convert(double value, std::string_view from, std::string_view to) {
  const Unit f = parse(from), t = parse(to);
  if (f.dim != t.dim) {
    throw InputError(
        fmt::format("unit '{}' ({}) cannot be converted to '{}' ({})", from, describe(f.dim), to, describe(t.dim)));
  }
  return value * f.to_si / t.to_si;
}

}  // namespace suite::units
