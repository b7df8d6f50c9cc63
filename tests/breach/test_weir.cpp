// The breach outflow law against critical-flow theory (docs/methods/breach.md, Fread 1988).
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/breach/hydraulics/weir.hpp"

namespace {

using suite::breach::critical_discharge;
using suite::breach::weir_discharge;
constexpr double g = 9.81;

TEST(Weir, CoefficientsAreTheCriticalFlowValues) {
  // Unit width, unit head: Q = c1; unit side slope, no bottom: Q = c2 (spec: 1.705 and 1.268).
  EXPECT_NEAR(weir_discharge(1.0, 0.0, 1.0, g), 1.705, 5e-4);
  EXPECT_NEAR(weir_discharge(0.0, 1.0, 1.0, g), 1.268, 5e-4);
  EXPECT_EQ(weir_discharge(3.0, 1.0, 0.0, g), 0.0);
  EXPECT_EQ(weir_discharge(3.0, 1.0, -0.5, g), 0.0) << "no flow below the invert";
}

TEST(Weir, ExactForRectangularAndTriangularSections) {
  // Each term is the exact critical-flow solution of its limit, to the bisection's round-off.
  for (double h : {0.01, 0.3, 2.0, 7.5}) {
    EXPECT_NEAR(weir_discharge(4.0, 0.0, h, g) / critical_discharge(4.0, 0.0, h, g), 1.0, 1e-12);
    EXPECT_NEAR(weir_discharge(0.0, 2.5, h, g) / critical_discharge(0.0, 2.5, h, g), 1.0, 1e-12);
  }
}

TEST(Weir, TrapezoidsWithinTheSuperpositionError) {
  // Adding the two limits is an approximation for a trapezoid; swept over b / (s h) from 1e-3
  // to 1e3 its largest deviation from exact critical flow is 2.2 %, near b = s h.
  double worst = 0.0;
  for (double ratio = 1e-3; ratio < 1e3; ratio *= 1.05) {
    const double h = 1.7, s = 2.0, b = ratio * s * h;
    worst = std::max(worst, std::abs(weir_discharge(b, s, h, g) / critical_discharge(b, s, h, g) - 1.0));
  }
  EXPECT_LT(worst, 0.0225);
  EXPECT_GT(worst, 0.02) << "the sweep reaches the worst case";
}

TEST(Weir, ScalesWithHeadAsFroudeSimilarityRequires) {
  // Geometric similarity at critical flow: doubling every length multiplies Q by 2^2.5.
  const double q1 = critical_discharge(2.0, 1.5, 1.0, g), q2 = critical_discharge(4.0, 1.5, 2.0, g);
  EXPECT_NEAR(q2 / q1, std::pow(2.0, 2.5), 1e-9);
  EXPECT_NEAR(weir_discharge(4.0, 1.5, 2.0, g) / weir_discharge(2.0, 1.5, 1.0, g), std::pow(2.0, 2.5), 1e-12);
}

}  // namespace
