// Tables of rows (x, y), linear between rows: values at and between the rows, the two ways of
// continuing outside them, the slope, the inverse and the exact integral, and the messages for
// a bad table.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "core/tables/piecewise_linear.hpp"
#include "tests/support/test_dirs.hpp"

using suite::PiecewiseLinear;
using suite::testing::input_error_of;

namespace {

const PiecewiseLinear::Names kNames{"test table", "level", "m", "volume", "m^3"};

// y = 2x on [0, 1], then 2 + 6 (x - 1) on [1, 3]: two segments with slopes 2 and 6.
PiecewiseLinear two_slopes() {
  return {{0, 1, 3}, {0, 2, 14}, kNames, PiecewiseLinear::Values::increasing};
}

TEST(PiecewiseLinear, InterpolatesBetweenRowsAndContinuesOutsideThem) {
  const auto f = two_slopes();
  for (double x : {0.0, 1.0, 3.0}) EXPECT_DOUBLE_EQ(f.clamped(x), f.extended(x)) << "the rows themselves";
  EXPECT_DOUBLE_EQ(f.extended(0.25), 0.5);
  EXPECT_DOUBLE_EQ(f.extended(2.0), 8.0);
  EXPECT_DOUBLE_EQ(f.clamped(-1.0), 0.0) << "held at the first value";
  EXPECT_DOUBLE_EQ(f.clamped(5.0), 14.0) << "held at the last value";
  EXPECT_DOUBLE_EQ(f.extended(-1.0), -2.0) << "the first segment continued";
  EXPECT_DOUBLE_EQ(f.extended(5.0), 26.0) << "the last segment continued";
  EXPECT_DOUBLE_EQ(f.slope(-1.0), 2.0);
  EXPECT_DOUBLE_EQ(f.slope(0.5), 2.0);
  EXPECT_DOUBLE_EQ(f.slope(1.0), 6.0) << "a row belongs to the segment above it";
  EXPECT_DOUBLE_EQ(f.slope(9.0), 6.0);
}

TEST(PiecewiseLinear, InverseUndoesExtendedEverywhere) {
  const auto f = two_slopes();
  for (double x : {-2.0, 0.0, 0.3, 1.0, 2.5, 3.0, 7.0}) EXPECT_NEAR(f.inverse(f.extended(x)), x, 1e-14) << x;
}

// The integral of a piecewise-linear function is exact by the trapezoid rule on each segment.
TEST(PiecewiseLinear, IntegralIsExact) {
  const auto f = two_slopes();
  EXPECT_DOUBLE_EQ(f.integral(0.0), 0.0);
  EXPECT_DOUBLE_EQ(f.integral(1.0), 1.0);          // x^2 on [0, 1]
  EXPECT_DOUBLE_EQ(f.integral(2.0), 1.0 + 5.0);    // + (2 + 8) / 2
  EXPECT_DOUBLE_EQ(f.integral(3.0), 1.0 + 16.0);   // + (2 + 14) / 2 * 2
  EXPECT_DOUBLE_EQ(f.integral(4.0), 17.0 + 14.0);  // the last value held
  EXPECT_DOUBLE_EQ(f.integral(-1.0), 0.0) << "the first value (0) held below";
}

TEST(PiecewiseLinear, BadTablesNameTheTableAndTheRow) {
  using V = PiecewiseLinear::Values;
  EXPECT_EQ(input_error_of([] { PiecewiseLinear({1}, {1}, kNames, V::increasing); }),
            "the test table needs at least 2 rows of [level, volume]");
  EXPECT_EQ(input_error_of([] {
              PiecewiseLinear({0, 2, 1}, {0, 1, 2}, kNames, V::increasing);
            }),
            "test table: levels must increase, but row 3 (1 m) does not come after row 2 (2 m)");
  EXPECT_EQ(input_error_of([] {
              PiecewiseLinear({0, 1, 2}, {0, 1, 1}, kNames, V::increasing);
            }),
            "test table: volumes must increase, but row 3 (1 m^3) does not exceed row 2 (1 m^3)");
  EXPECT_EQ(input_error_of([] { PiecewiseLinear({0, 1, 2}, {0, 1, 1}, kNames, V::nondecreasing); }), "");
  EXPECT_EQ(input_error_of([] {
              PiecewiseLinear({0, 1, 2}, {0, 2, 1}, kNames, V::nondecreasing);
            }),
            "test table: volumes must not fall, but row 3 (1 m^3) is below row 2 (2 m^3)");
  EXPECT_EQ(input_error_of([] {
              PiecewiseLinear({0, 1}, {0, -1}, kNames, V::nonnegative);
            }),
            "test table: row 2 has a negative volume (-1 m^3)");
  EXPECT_EQ(input_error_of([] { PiecewiseLinear({0}, {3}, kNames, V::nonnegative, 1); }), "")
      << "one row is a table where the caller allows it";
}

}  // namespace
