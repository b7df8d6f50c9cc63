// Templates and their expressions (docs/methods/studies.md, "Templates"): the arithmetic agrees with
// Python's, the dissertation's WinDAM C template renders exactly, and mistakes are reported with
// their place.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "studies/template/expression.hpp"
#include "studies/template/template.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::studies::evaluate_expression;
using suite::studies::Expression;
using suite::studies::format_number;
using suite::studies::Template;

using suite::testing::input_error_of;

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

const std::map<std::string, double> kVariables = {{"x", 0.7}, {"y", 2.5}, {"Kd", 300.0}, {"Us", 70.0}, {"Scale", 3.0}};

// Every operator, precedence and associativity rule, function and constant of the template
// syntax (docs/methods/studies.md, "Templates").
const std::vector<std::string> kExpressions = {
    "1 + 2 * 3",
    "(1 + 2) * 3",
    "7 - 4 - 2",
    "100 / 8 / 2",
    "2 ** 3 ** 2",
    "-2 ** 2",
    "(-2) ** 2",
    "2 ** -1",
    "-2 ** -2",
    "--2 ** 2",
    "2 ** 3 * 2",
    "2 * 3 ** 2",
    "2 ** 0.5 ** 2",
    "-x ** 2",
    "2 * -3",
    "2 - -3",
    "+3 - +2",
    "1 / 3",
    "0.1 + 0.2",
    "7 // 2",
    "-7 // 2",
    "7 // -2",
    "7.5 // 2",
    "-x // 0.2",
    "7 % 3",
    "-7 % 3",
    "7 % -3",
    "-7.5 % 2",
    "x % 0.3",
    "2 * 3 % 4",
    "2 + 3 % 4 * 5 // 3",
    "x ** 2 + y ** 2",
    "sin(x) + cos(y) * tan(0.3)",
    "asin(0.5) + acos(0.25) + atan(-2)",
    "sinh(1) - cosh(0.5) + tanh(-0.3)",
    "exp(x) + log(y) + log10(1000)",
    "log(8, 2) + log(Kd, 10)",
    "sqrt(Kd) * abs(-Us)",
    "floor(-2.5) + ceil(-2.5) + floor(x) + ceil(y)",
    "min(x, y, 3) - max(1, Kd, Us)",
    "pow(2, 10) + pow(x, 0.5)",
    "pi * e - pi / 2",
    "4*(2**Scale)",
    "1e-3 * 2.5e2 + .5 + 3. + 1E+2",
    "Kd / Us ** 0.5 - Scale * (Kd - Us) / 7",
    "((x + 1) * 2 - y) / (Scale - 0.5)",
};

// Python's values of kExpressions, from /usr/bin/python3 itself.
std::vector<double> python_values() {
  std::string script = "from math import *\nx=0.7; y=2.5; Kd=300.0; Us=70.0; Scale=3.0\nfor s in [";
  for (const auto& e : kExpressions) script += "\"" + e + "\",";
  script += "]: print(repr(float(eval(s))))\n";
  const std::string command = "/usr/bin/python3 -c '" + script + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {};
  std::vector<double> values;
  char line[128];
  while (std::fgets(line, sizeof line, pipe)) values.push_back(std::strtod(line, nullptr));
  pclose(pipe);
  return values;
}

TEST(Expression, AgreesWithPython) {
  const auto expected = python_values();
  ASSERT_EQ(expected.size(), kExpressions.size()) << "could not run /usr/bin/python3";
  for (std::size_t i = 0; i < kExpressions.size(); ++i) {
    const double got = evaluate_expression(kExpressions[i], kVariables);
    // Python and muParser call the same C library, so only rounding order could differ.
    EXPECT_LE(std::fabs(got - expected[i]), 1e-12 * std::fabs(expected[i]))
        << kExpressions[i] << " = " << got << ", Python: " << expected[i];
  }
}

TEST(Expression, PrecedenceOfPower) {
  EXPECT_EQ(evaluate_expression("-2**2", {}), -4.0);
  EXPECT_EQ(evaluate_expression("2**3**2", {}), 512.0);
  EXPECT_EQ(evaluate_expression("2**-1", {}), 0.5);
  EXPECT_EQ(evaluate_expression("(-2)**2", {}), 4.0);
}

TEST(Expression, VariablesTakeThePlaceOfConstants) {
  EXPECT_DOUBLE_EQ(evaluate_expression("e", {}), std::exp(1.0));
  EXPECT_EQ(evaluate_expression("e", {{"e", 0.6}}), 0.6);  // a void ratio, say
  const auto expr = Expression::compile("pi * r**2 + e");
  EXPECT_EQ(expr.names(), (std::vector<std::string>{"r"}));
  const Expression copy = expr;
  EXPECT_EQ(copy.evaluate({{"r", 1.0}, {"e", 0.0}}), expr.evaluate({{"r", 1.0}, {"e", 0.0}}));
}

TEST(Expression, MistakesNameTheCharacter) {
  const auto bad_syntax = input_error_of([] { evaluate_expression("2 +* 3", {}); });
  EXPECT_CONTAINS(bad_syntax, "expression \"2 +* 3\", character 4: unexpected '*'");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("(1 + 2", {}); }), "character 1: '(' is never closed");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("2 ^ 3", {}); }), "character 3: '^' is not a power");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("sin(1, 2)", {}); }), "sin() takes 1 argument, not 2");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("flor(1)", {}); }), "unknown function 'flor'");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("2x", {}); }), "character 1: invalid number '2x'");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("", {}); }), "empty expression");
  EXPECT_CONTAINS(input_error_of([] { evaluate_expression("1 + zeta", kVariables); }),
                  "character 5: unknown variable 'zeta'; valid names: Kd, Scale, Us, x, y");
}

TEST(FormatNumber, PrintsTenSignificantDigits) {
  EXPECT_EQ(format_number(32.0), "32");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.3");
  EXPECT_EQ(format_number(1e-20), "1e-20");
  EXPECT_EQ(format_number(-2.5), "-2.5");
  EXPECT_EQ(format_number(1234567.891234), "1234567.891");
}

// The WinDAM C input of the dissertation's study (docs/methods/studies.md), fixed columns and all.
const std::string kWinDam =
    "IEMODEL 2 120 {Kd} {Us} 0.2\n"
    "CRESTPRFL\n"
    "0 {4*(2**Scale)}\n"
    "900 {4*(2**Scale)}\n"
    "CONDUIT 0.2 0.2 {(2**Scale)} 450\n";

TEST(Template, RendersTheWinDamInput) {
  const auto t = Template::parse(kWinDam, "windam.in");
  EXPECT_EQ(t.names(), (std::vector<std::string>{"Kd", "Scale", "Us"}));
  EXPECT_EQ(t.render({{"Kd", 300}, {"Us", 70}, {"Scale", 3}}),
            "IEMODEL 2 120 300 70 0.2\n"
            "CRESTPRFL\n"
            "0 32\n"
            "900 32\n"
            "CONDUIT 0.2 0.2 8 450\n");
  // Parsed once, rendered many times with other values (and by a copy).
  const Template copy = t;
  for (int scale = 0; scale < 5; ++scale) {
    const auto text = copy.render({{"Kd", 1700}, {"Us", 0.3}, {"Scale", scale}});
    EXPECT_CONTAINS(text, "IEMODEL 2 120 1700 0.3 0.2\n");
    EXPECT_CONTAINS(text, "\n0 " + format_number(4 * std::pow(2.0, scale)) + "\n");
  }
}

TEST(Template, KeepsSpacingAndEscapes) {
  const auto t = Template::parse("  {Kd}\t\t{ Us }  \r\n\\{Kd\\} = {Kd}; C:\\dir\\f{x}\n", "in.txt");
  EXPECT_EQ(t.render({{"Kd", 300}, {"Us", 70}, {"x", 0.5}}), "  300\t\t70  \r\n{Kd} = 300; C:\\dir\\f0.5\n");
  EXPECT_EQ(Template::parse("no tags \\{\\{here\\}", "in.txt").render({}), "no tags {{here}");
  EXPECT_EQ(Template::parse("{pi*x} {e}", "in.txt").names(), (std::vector<std::string>{"x"}));
}

TEST(Template, MistakesNameTheLineAndColumn) {
  EXPECT_CONTAINS(input_error_of([] { Template::parse("a\n  {Kd\nb", "in.txt"); }), "in.txt:2:3: unmatched '{'");
  EXPECT_CONTAINS(input_error_of([] { Template::parse("a {Kd {Us}", "in.txt"); }), "in.txt:1:3: unmatched '{'");
  EXPECT_CONTAINS(input_error_of([] { Template::parse("a } b", "in.txt"); }), "in.txt:1:3: unmatched '}'");
  EXPECT_CONTAINS(input_error_of([] { Template::parse("line\nvalue {4*(2**}", "in.txt"); }),
                  "in.txt:2:14: in {4*(2**}: unexpected end of expression");
  EXPECT_CONTAINS(input_error_of([] { Template::parse("{2 +* 3}", "in.txt"); }), "in.txt:1:5: in {2 +* 3}");
  const auto t = Template::parse(kWinDam + "X {Kdx}\n", "windam.in");
  EXPECT_CONTAINS(input_error_of([&] {
                    t.render({{"Kd", 300}, {"Us", 70}, {"Scale", 3}});
                  }),
                  "windam.in:6:4: in {Kdx}: unknown variable 'Kdx' (did you mean 'Kd'?); valid names: Kd, Scale, Us");
}

// Where Python raises, the template does too, naming the place and the values: the expression
// gives inf or nan, which no input file can take.
TEST(Template, ValuesWherePythonRaisesAreRefused) {
  const auto t = Template::parse("kd = {Kd/0}\nroot = {(-8)**(1/3)}\n", "dam.tmpl");
  EXPECT_CONTAINS(input_error_of([&] {
                    t.render({{"Kd", 3}});
                  }),
                  "dam.tmpl:1:7: {Kd/0} gives inf at Kd = 3: Python raises here");
  const auto root = Template::parse("root = {(x)**(1/3)}\n", "dam.tmpl");
  EXPECT_EQ(root.render({{"x", 8}}), "root = 2\n");
  EXPECT_CONTAINS(input_error_of([&] { root.render({{"x", -8}}); }), "{(x)**(1/3)} gives nan at x = -8");
}

}  // namespace
