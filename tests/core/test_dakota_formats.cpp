// Dakota's file formats, byte for byte against files Dakota itself wrote or tests against.
//
// Sources of the expected bytes:
// - parameters files: snl-dakota/dakota interfaces/Python/dakota_interfacing_test.py
//   (dakotaParams, apreproParams, dakotaBatchParams: Dakota 6.16+ layout with metadata);
// - results files: the same test (test_ignore_asv, test_results_write: "%24.16E %s", "FAIL");
// - tabular files: snl-dakota/dakota-examples
//   official/drivers/black-box_simulation_windows/dakota_tabular.dat (current Dakota,
//   left-aligned) and official/surrogates/imported/training_data.dat (older, right-aligned).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "core/dakota/parameters_file.hpp"
#include "core/dakota/results_file.hpp"
#include "core/dakota/tabular_file.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::dakota;

using suite::testing::input_error_of;

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---- parameters files ----

// dakota_interfacing_test.py, dakotaBatchParams, first evaluation (verbatim).
const std::string kDakotaBatchEval1 =
    "                                          2 variables\n"
    "                      2.109465794009156e-01 x1\n"
    "                     -9.675715913879684e-01 x2\n"
    "                                          1 functions\n"
    "                                          1 ASV_1:obj_fn\n"
    "                                          2 derivative_variables\n"
    "                                          1 DVV_1:x1\n"
    "                                          2 DVV_2:x2\n"
    "                                          0 analysis_components\n"
    "                                        1:1 eval_id\n"
    "                                          1 metadata\n"
    "                                    seconds MD_1\n";

// dakota_interfacing_test.py, dakotaParams with ASV 1 (verbatim): its third variable is a
// string, which the suite does not support.
const std::string kDakotaParams =
    "                                          3 variables\n"
    "                      7.488318331306800e-01 x1\n"
    "                      2.188638686202466e-01 x2\n"
    "                                    foo bar dussv_1\n"
    "                                          1 functions\n"
    "                                          1 ASV_1:response_fn_1\n"
    "                                          2 derivative_variables\n"
    "                                          1 DVV_1:x1\n"
    "                                          2 DVV_2:x2\n"
    "                                          2 analysis_components\n"
    "                                        a b AC_1:first.sh\n"
    "                                          b AC_2:first.sh\n"
    "                                          1 eval_id\n"
    "                                          1 metadata\n"
    "                                    seconds MD_1\n";

// The same file without the string variable (its line removed, the count 3 -> 2).
const std::string kDakotaParamsReals =
    "                                          2 variables\n"
    "                      7.488318331306800e-01 x1\n"
    "                      2.188638686202466e-01 x2\n"
    "                                          1 functions\n"
    "                                          1 ASV_1:response_fn_1\n"
    "                                          2 derivative_variables\n"
    "                                          1 DVV_1:x1\n"
    "                                          2 DVV_2:x2\n"
    "                                          2 analysis_components\n"
    "                                        a b AC_1:first.sh\n"
    "                                          b AC_2:first.sh\n"
    "                                          1 eval_id\n"
    "                                          1 metadata\n"
    "                                    seconds MD_1\n";

// dakota_interfacing_test.py, apreproParams with ASV 1, the string variable removed likewise.
const std::string kApreproParamsReals =
    "                    { DAKOTA_VARS     =                      2 }\n"
    "                    { x1              =  7.488318331306800e-01 }\n"
    "                    { x2              =  2.188638686202466e-01 }\n"
    "                    { DAKOTA_FNS      =                      1 }\n"
    "                    { ASV_1:response_fn_1 =                      1 }\n"
    "                    { DAKOTA_DER_VARS =                      2 }\n"
    "                    { DVV_1:x1        =                      1 }\n"
    "                    { DVV_2:x2        =                      2 }\n"
    "                    { DAKOTA_AN_COMPS =                      2 }\n"
    "                    { AC_1:first.sh   =                      \"a b\" }\n"
    "                    { AC_2:first.sh   =                      \"b\" }\n"
    "                    { DAKOTA_EVAL_ID  =                      1 }\n"
    "                    { DAKOTA_METADATA =                      1 }\n"
    "                    { MD_1            =                      \"seconds\" }\n";

Parameters example_parameters() {
  Parameters p;
  p.variables = {{"x1", 7.488318331306800e-01}, {"x2", 2.188638686202466e-01}};
  p.responses = {"response_fn_1"};
  p.analysis_components = {"a b", "b"};
  p.analysis_driver = "first.sh";
  p.eval_id = "1";
  p.metadata = {"seconds"};
  return p;
}

TEST(DakotaParameters, StandardIsByteExact) {
  Parameters p;
  p.variables = {{"x1", 2.109465794009156e-01}, {"x2", -9.675715913879684e-01}};
  p.responses = {"obj_fn"};
  p.eval_id = "1:1";
  p.metadata = {"seconds"};
  EXPECT_EQ(write_parameters(p, ParametersFormat::standard), kDakotaBatchEval1);
  EXPECT_EQ(write_parameters(example_parameters(), ParametersFormat::standard), kDakotaParamsReals);
}

TEST(DakotaParameters, ApreproIsByteExact) {
  EXPECT_EQ(write_parameters(example_parameters(), ParametersFormat::aprepro), kApreproParamsReals);
}

TEST(DakotaParameters, ReadsBothLayouts) {
  for (const auto& text : {kDakotaParamsReals, kApreproParamsReals}) {
    const auto p = read_parameters(text, "params.in");
    ASSERT_EQ(p.variables.size(), 2u);
    EXPECT_EQ(p.variables[0].first, "x1");
    EXPECT_EQ(p.variables[0].second, 7.488318331306800e-01);
    EXPECT_EQ(p.variables[1].second, 2.188638686202466e-01);
    EXPECT_EQ(p.responses, std::vector<std::string>{"response_fn_1"});
    EXPECT_EQ(p.asv, std::vector<int>{1});
    EXPECT_EQ(p.derivative_variables, (std::vector<std::string>{"x1", "x2"}));
    EXPECT_EQ(p.analysis_components, (std::vector<std::string>{"a b", "b"}));
    EXPECT_EQ(p.analysis_driver, "first.sh");
    EXPECT_EQ(p.eval_id, "1");
    EXPECT_EQ(p.metadata, std::vector<std::string>{"seconds"});
  }
  EXPECT_EQ(detect_parameters_format(kApreproParamsReals), ParametersFormat::aprepro);
  EXPECT_EQ(detect_parameters_format(kDakotaParamsReals), ParametersFormat::standard);
  // Reading what was read and writing it again gives the same bytes.
  EXPECT_EQ(write_parameters(read_parameters(kApreproParamsReals, "p"), ParametersFormat::aprepro),
            kApreproParamsReals);
}

TEST(DakotaParameters, ReadsPre616FilesWithoutMetadata) {
  // Dakota 6.15 and older end after eval_id.
  const auto cut = kDakotaBatchEval1.substr(0, kDakotaBatchEval1.rfind('\n', kDakotaBatchEval1.find(" metadata")) + 1);
  const auto p = read_parameters(cut, "params.in");
  EXPECT_EQ(p.eval_id, "1:1");
  EXPECT_TRUE(p.metadata.empty());
}

TEST(DakotaParameters, RefusesStringVariablesAndBatches) {
  EXPECT_TRUE(contains(input_error_of([] { read_parameters(kDakotaParams, "params.in"); }),
                       "params.in:4: the value \"foo bar\" of variable \"dussv_1\""));
  EXPECT_TRUE(contains(input_error_of([] { read_parameters(kDakotaBatchEval1 + kDakotaBatchEval1, "batch.in"); }),
                       "batch.in:13: a second evaluation follows"));
}

TEST(DakotaParameters, DefaultsAsvOneAndEveryVariableDerivative) {
  Parameters p;
  p.variables = {{"a", 1.0}, {"b", 2.0}, {"c", 3.0}};
  p.responses = {"f", "g"};
  auto back = read_parameters(write_parameters(p, ParametersFormat::standard), "p");
  EXPECT_EQ(back.asv, (std::vector<int>{1, 1}));
  EXPECT_EQ(back.derivative_variables, (std::vector<std::string>{"a", "b", "c"}));
  p.asv = {3, 0};
  p.derivative_variables = {"c"};
  const auto text = write_parameters(p, ParametersFormat::standard);
  EXPECT_TRUE(contains(text, "                                          3 DVV_1:c\n"));
  back = read_parameters(text, "p");
  EXPECT_EQ(back.asv, (std::vector<int>{3, 0}));
  EXPECT_EQ(back.derivative_variables, std::vector<std::string>{"c"});
}

TEST(DakotaParameters, RoundTripsTo15SignificantDigits) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-10, 10);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (auto format : {ParametersFormat::standard, ParametersFormat::aprepro}) {
    Parameters p;
    for (int i = 0; i < 200; ++i)
      p.variables.emplace_back(fmt::format("v{}", i), mantissa(rng) * std::pow(10.0, exponent(rng)));
    p.variables.emplace_back("zero", 0.0);
    p.variables.emplace_back("tiny", 4.9e-324);
    p.variables.emplace_back("huge", -1.797693134862315e308);
    p.responses = {"peak_flow", "breach_width"};
    p.eval_id = "12:345";
    const auto back = read_parameters(write_parameters(p, format), "p");
    ASSERT_EQ(back.variables.size(), p.variables.size());
    for (std::size_t i = 0; i < p.variables.size(); ++i) {
      EXPECT_EQ(back.variables[i].first, p.variables[i].first);
      EXPECT_NEAR(back.variables[i].second, p.variables[i].second, 1e-15 * std::abs(p.variables[i].second))
          << p.variables[i].first;
    }
    EXPECT_EQ(back.responses, p.responses);
    EXPECT_EQ(back.eval_id, "12:345");
  }
}

TEST(DakotaParameters, WriteRefusesWhatCannotBeReadBack) {
  auto p = example_parameters();
  p.variables[0].first = "two words";
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::standard); }), "\"two words\""));
  p = example_parameters();
  p.variables[1].second = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::standard); }), "not finite"));
  p.variables[1].second = std::numeric_limits<double>::max();  // rounds up to 1.797693134862316e+308
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::standard); }), "largest double"));
  p = example_parameters();
  p.eval_id = "1.2";
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::aprepro); }), "eval_id"));
  p = example_parameters();
  p.asv = {1, 1};
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::standard); }), "2 ASV entries"));
  p = example_parameters();
  p.derivative_variables = {"x3"};
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::standard); }), "\"x3\""));
  p = example_parameters();
  p.analysis_components = {"say \"hi\""};
  EXPECT_TRUE(contains(input_error_of([&] { write_parameters(p, ParametersFormat::aprepro); }), "without '\"'"));
}

TEST(DakotaParameters, MalformedFilesNameTheLine) {
  const auto error = [](const std::string& text) { return input_error_of([&] { read_parameters(text, "p.in"); }); };
  EXPECT_TRUE(contains(error(""), "p.in:1: the file ends where the \"variables\" line was expected"));
  EXPECT_TRUE(contains(error("2 variables\n1.0 x\n"), "p.in:2: the file ends where variable 2 of 2"));
  EXPECT_TRUE(contains(error("1 functions\n"), "p.in:1: expected \"<count> variables\", found \"1 functions\""));
  EXPECT_TRUE(contains(error("1 variables\n1.0e x\n"), "p.in:2: the value \"1.0e\" of variable \"x\""));
  EXPECT_TRUE(contains(error("1 variables\nnan x\n"), "not a finite real number"));
  EXPECT_TRUE(contains(error("1 variables\n1 x\n1 functions\n9 ASV_1:f\n"), "p.in:4: the ASV \"9\""));
  EXPECT_TRUE(contains(error("1 variables\n1 x\n1 functions\n1 f\n"), "p.in:4: expected the tag \"ASV_1:<response>\""));
  EXPECT_TRUE(contains(error("1 variables\n1 x\n0 functions\n1 derivative_variables\n2 DVV_1:y\n"),
                       "p.in:5: the derivative variable id \"2\" is not between 1 and 1"));
  EXPECT_TRUE(contains(error("1 variables\n1 x\n0 functions\n0 derivative_variables\n0 analysis_components\n"
                             "one eval_id\n"),
                       "p.in:6: expected the evaluation id"));
  EXPECT_TRUE(contains(error("1 variables\n1 x\n0 functions\n0 derivative_variables\n0 analysis_components\n"
                             "1 eval_id\n0 metadata\nextra stuff\n"),
                       "p.in:8: unexpected text"));
  EXPECT_TRUE(contains(error("{ DAKOTA_VARS = 1 }\n{ x = 1.0\n"), "p.in:2: expected \"{ <tag> = <value> }\""));
  EXPECT_TRUE(contains(error("{ DAKOTA_VARS = 1 }\n{ x = \"1.0 }\n"), "p.in:2: unterminated quoted value"));
}

// ---- results files ----

TEST(DakotaResults, WriteIsByteExact) {
  // dakota_interfacing_test.py, test_ignore_asv.
  EXPECT_EQ(write_results({{"response_fn_1", 5.0}, {"seconds", 42.0}}),
            "  5.0000000000000000E+00 response_fn_1\n  4.2000000000000000E+01 seconds\n");
  // test_results_write: a failure is the single word FAIL.
  EXPECT_EQ(write_failure(), "FAIL\n");
  EXPECT_EQ(write_results({{"", -1.0e-300}}), "-1.0000000000000000E-300\n");  // 24 wide: no padding
}

TEST(DakotaResults, ReadsValuesWithOptionalLabels) {
  // Dakota's flexible reading: a label is optional and several values may share a line.
  const auto r = read_results("  5.0000000000000000E+00 response_fn_1\n4.2e1\n\n-3 c 7 +0.5 e\n", "results.out", 5);
  EXPECT_FALSE(r.failed);
  EXPECT_EQ(r.values, (std::vector<double>{5.0, 42.0, -3.0, 7.0, 0.5}));
  EXPECT_EQ(r.labels, (std::vector<std::string>{"response_fn_1", "", "c", "", "e"}));
}

TEST(DakotaResults, RoundTripsExactly) {
  const std::vector<std::pair<std::string, double>> in = {
      {"peak_flow", 1.0 / 3.0}, {"time", 6.02214076e23}, {"tiny", 4.9e-324}, {"neg", -2.5e-7}};
  const auto r = read_results(write_results(in), "results.out", in.size());
  ASSERT_EQ(r.values.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(r.labels[i], in[i].first);
    EXPECT_NEAR(r.values[i], in[i].second, 1e-15 * std::abs(in[i].second));
  }
}

TEST(DakotaResults, FailMarkerInAnyCase) {
  for (const std::string text : {"FAIL\n", "fail", "  \n Failed: solver diverged\n", "FaIl 1.0 f\n"}) {
    const auto r = read_results(text, "results.out", 2);
    EXPECT_TRUE(r.failed) << text;
    EXPECT_TRUE(r.values.empty());
  }
  EXPECT_TRUE(contains(input_error_of([] { read_results("fai\n", "r.out", 1); }), "r.out:1: \"fai\" is not a number"));
}

TEST(DakotaResults, MalformedFilesNameTheLine) {
  const auto error = [](const std::string& text, std::size_t n) {
    return input_error_of([&] { read_results(text, "r.out", n); });
  };
  EXPECT_TRUE(contains(error("1.0 f\nabc\n", 2), "r.out:2: \"abc\" is not a number"));
  EXPECT_TRUE(contains(error("1.0 f g\n", 2), "r.out:1: \"g\" is not a number"));
  EXPECT_TRUE(contains(error("1.0 f\n\n", 2), "r.out:1: expected 2 function value(s) but found 1"));
  EXPECT_TRUE(contains(error("", 1), "r.out:1: expected 1 function value(s) but found 0"));
  EXPECT_TRUE(contains(error("1.0 f\nnan g\n", 2), "r.out:2: function value \"nan\" is not a finite number"));
  EXPECT_TRUE(contains(error("1.0 f\n-inf g\n", 2), "not a finite number"));
  EXPECT_TRUE(contains(error("1 a\n2 b\n3 c\n", 2), "r.out:3: more function values than the 2 expected"));
  EXPECT_TRUE(contains(error("1 a\n[ 1 2 ]\n", 1), "r.out:2: gradient or Hessian data"));
  EXPECT_TRUE(contains(input_error_of([] { write_results({{"f", std::nan("")}}); }), "report a failed evaluation"));
}

// ---- tabular files ----

// dakota_tabular.dat of the black-box example: its header and its rows 1 and 20 (verbatim).
const std::string kBlackBoxTabular =
    "%eval_id interface w              t              L              p              E              X              Y "
    "             mass           stress         displacement   \n"
    "1        NO_ID      1              1              10             500            29000000       5              5 "
    "             2.893518519    600            0.0009753196982 \n"
    "20       NO_ID      1              1              9              500            29000000       5              5 "
    "             2.604166667    540            0.00071100806  \n";

TEST(DakotaTabular, WriteIsByteExact) {
  std::ostringstream out;
  TabularWriter t(out, {"w", "t", "L", "p", "E", "X", "Y"}, {"mass", "stress", "displacement"});
  t.row(1, "", {1, 1, 10, 500, 29000000, 5, 5}, {2.893518519, 600, 0.0009753196982});
  t.row(20, "", {1, 1, 9, 500, 29000000, 5, 5}, {2.604166667, 540, 0.00071100806});
  EXPECT_EQ(out.str(), kBlackBoxTabular);
}

TEST(DakotaTabular, ReadsCurrentAndOlderLayouts) {
  auto rows = read_tabular(kBlackBoxTabular, "dakota_tabular.dat", 7);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].eval_id, 20);
  EXPECT_EQ(rows[1].interface_id, "");
  EXPECT_EQ(rows[1].variables, (std::vector<double>{1, 1, 9, 500, 29000000, 5, 5}));
  EXPECT_EQ(rows[1].responses, (std::vector<double>{2.604166667, 540, 0.00071100806}));
  // training_data.dat, first two rows (older Dakota: right-aligned values).
  rows = read_tabular(
      "%eval_id interface             x1             x2              f \n"
      "1        NO_ID    1.040428725   0.9481639439 9.891374515e-06 \n"
      "2        NO_ID    1.067546302   0.9390941226 3.457701524e-05 \n",
      "training_data.dat", 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].variables, (std::vector<double>{1.040428725, 0.9481639439}));
  EXPECT_EQ(rows[1].responses, std::vector<double>{3.457701524e-05});
}

TEST(DakotaTabular, RoundTripsTo10DigitsWithInterfaceIdsAndNaN) {
  std::ostringstream out;
  TabularWriter t(out, {"Kd", "Us"}, {"Qp", "Tf"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  t.row(1, "breach", {1.0 / 3.0, -2.5e-7}, {123456.789012345, 6.02214076e23});
  t.row(2, "", {1e-300, 7}, {nan, 1});  // a failure recovered as NaN
  const auto rows = read_tabular(out.str(), "t.dat", 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].interface_id, "breach");
  // 10 significant digits: a relative error of at most 5e-10.
  EXPECT_NEAR(rows[0].variables[0], 1.0 / 3.0, 5e-10 / 3);
  EXPECT_NEAR(rows[0].variables[1], -2.5e-7, 5e-10 * 2.5e-7);
  EXPECT_NEAR(rows[0].responses[0], 123456.789012345, 5e-10 * 123456.8);
  EXPECT_EQ(rows[0].responses[1], 6.02214076e23);
  EXPECT_TRUE(std::isnan(rows[1].responses[0]));
  EXPECT_TRUE(
      contains(out.str(), "\n2        NO_ID      1e-300         7              nan            1              \n"));
  // Dakota writes N/A for a response it did not compute; it reads as NaN.
  const auto na = read_tabular("%eval_id interface x f\n3 NO_ID 1 N/A\n", "t.dat", 1);
  EXPECT_TRUE(std::isnan(na[0].responses[0]));
}

TEST(DakotaTabular, WithoutInterfaceColumn) {
  std::ostringstream out;
  TabularWriter t(out, {"x"}, {"f"}, false);
  t.row(3, "", {0.5}, {2});
  EXPECT_EQ(out.str(), "%eval_id x              f              \n3        0.5            2              \n");
  EXPECT_EQ(read_tabular(out.str(), "t.dat", 1, false)[0].responses, std::vector<double>{2});
}

TEST(DakotaTabular, MalformedFilesNameTheLine) {
  const auto error = [](const std::string& text) { return input_error_of([&] { read_tabular(text, "t.dat", 1); }); };
  EXPECT_TRUE(contains(error(""), "t.dat:1: empty file"));
  EXPECT_TRUE(contains(error("x f\n1 NO_ID 1 2\n"), "t.dat:1: expected the annotated header"));
  EXPECT_TRUE(contains(error("%eval_id interface\n"), "t.dat:1: the header has 0 labels"));
  EXPECT_TRUE(contains(error("%eval_id interface x f\n1 NO_ID 1\n"), "t.dat:2: expected 4 columns"));
  EXPECT_TRUE(contains(error("%eval_id interface x f\n\n1 NO_ID 1 two\n"), "t.dat:3: column 4 \"two\""));
  EXPECT_TRUE(contains(error("%eval_id interface x f\n1.5 NO_ID 1 2\n"), "t.dat:2: the evaluation id \"1.5\""));
  std::ostringstream out;
  TabularWriter t(out, {"x"}, {"f"});
  EXPECT_TRUE(contains(input_error_of([&] { t.row(1, "", {1, 2}, {3}); }), "row 1 has 2 variables"));
  EXPECT_TRUE(contains(input_error_of([&] { TabularWriter(out, {"a b"}, {}); }), "\"a b\""));
}

}  // namespace
