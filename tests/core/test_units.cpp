// Unit parsing and conversion against exact definitions (NIST SP 811: 1 ft = 0.3048 m,
// 1 lb = 0.45359237 kg, g0 = 9.80665 m/s^2).
#include <gtest/gtest.h>

#include "core/config/units.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

namespace u = suite::units;

namespace {

// Conversions chain a few multiplications of exact decimal factors: a few ulps.
constexpr double kRel = 1e-14;

TEST(Units, ExactDefinitions) {
  EXPECT_NEAR(u::convert(1.0, "ft", "m"), 0.3048, 0.3048 * kRel);
  EXPECT_NEAR(u::convert(1.0, "cfs", "m^3/s"), 0.3048 * 0.3048 * 0.3048, kRel);
  EXPECT_NEAR(u::convert(1.0, "ft3/s", "cfs"), 1.0, kRel);
  EXPECT_NEAR(u::convert(1.0, "lbf", "N"), 0.45359237 * 9.80665, 1e-12);
  EXPECT_NEAR(u::convert(1.0, "psf", "lbf/ft^2"), 1.0, kRel);
  EXPECT_NEAR(u::convert(1.0, "psi", "lbf/in^2"), 1.0, kRel);
  EXPECT_NEAR(u::convert(1.0, "g/cm^3", "kg/m3"), 1000.0, 1000 * kRel);
  EXPECT_NEAR(u::convert(2.0, "h", "s"), 7200.0, 0.0);
  EXPECT_NEAR(u::convert(180.0, "deg", "rad"), 3.14159265358979323846, kRel);
}

TEST(Units, CompoundExpressions) {
  // Erodibility kd: cm^3/(N s) to m^3/(N*s).
  EXPECT_NEAR(u::convert(1.0, "cm^3/(N s)", "m^3/(N*s)"), 1e-6, 1e-6 * kRel);
  EXPECT_NEAR(u::convert(1.0, "ft/h/psf", "m/s/Pa"), 0.3048 / 3600.0 / 47.88025898033584, 1e-18);
  EXPECT_NEAR(u::convert(1.0, "kN.m", "N*m"), 1000.0, 1e-10);
  EXPECT_NEAR(u::convert(3.0, "1/s", "1/min"), 180.0, 1e-12);
  EXPECT_NEAR(u::convert(1.0, "m s^-1", "m/s"), 1.0, 0.0);
}

TEST(Units, MismatchAndGarbageAreExplained) {
  using suite::testing::input_error_of;
  EXPECT_NE(input_error_of([] { u::convert(1, "m", "s"); }).find("'m' (length) cannot be converted to 's' (time)"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { u::parse("furlong"); }).find("unknown unit symbol 'furlong'"), std::string::npos);
  EXPECT_NE(input_error_of([] { u::parse("m/(s"); }).find("missing ')'"), std::string::npos);
  EXPECT_EQ(u::describe(u::parse("kg/m^3").dim), "mass/length^3");
}

}  // namespace
