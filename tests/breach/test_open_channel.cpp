// Flow down the face, through the breach and through an internal-erosion pipe: Manning normal depth, critical depth of
// a trapezoid, and the stresses the erosion law uses, against hand calculations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solvers/breach/hydraulics/open_channel.hpp"
#include "solvers/breach/hydraulics/pipe_flow.hpp"
#include "solvers/breach/hydraulics/weir.hpp"

namespace {

using namespace suite::breach;
constexpr double g = 9.81;

TEST(OpenChannel, NormalDepthSatisfiesManning) {
  for (double q : {0.01, 0.5, 4.0, 30.0})
    for (double slope : {0.05, 1.0 / 3.0, 0.8}) {
      const double n = 0.02, d = normal_depth(q, slope, n);
      EXPECT_NEAR(std::pow(d, 5.0 / 3.0) * std::sqrt(slope) / n, q, 1e-12 * q);
    }
  EXPECT_EQ(normal_depth(0.0, 0.3, 0.02), 0.0);
}

TEST(OpenChannel, NormalFlowStressByHand) {
  // q = 1 m^2/s on a 3H:1V face, n = 0.02: D = (0.02 / sqrt(1/3))^0.6 = 0.13297 m,
  // tau_0 = 1000 x 9.81 x D / 3 = 434.8 Pa; grain part with n_s = 0.01: a quarter of it.
  const double d = std::pow(0.02 / std::sqrt(1.0 / 3.0), 0.6);
  EXPECT_NEAR(d, 0.13297, 5e-5);
  const double tau0 = normal_flow_stress(1.0, 1.0 / 3.0, 0.02, g);
  EXPECT_NEAR(tau0, 1000.0 * g * d / 3.0, 1e-9);
  EXPECT_NEAR(effective_stress(tau0, 0.01, 0.02), tau0 / 4.0, 1e-12);
}

TEST(OpenChannel, CriticalDepthSolvesTheEnergyEquation) {
  EXPECT_DOUBLE_EQ(critical_depth(5.0, 0.0, 3.0), 2.0);  // rectangle: 2h/3
  for (double b : {0.0, 0.5, 10.0})
    for (double s : {0.5, 1.0, 3.0})
      for (double h : {0.05, 1.0, 12.0}) {
        const double y = critical_depth(b, s, h);
        const double area = (b + s * y) * y, top = b + 2.0 * s * y;
        EXPECT_NEAR(y + area / (2.0 * top), h, 1e-12 * h) << b << " " << s << " " << h;
        EXPECT_GE(y, 2.0 * h / 3.0 - 1e-15);
        EXPECT_LE(y, 0.8 * h + 1e-15);
        // The same critical flow as the bisection used to check the weir law.
        EXPECT_NEAR(std::sqrt(g * area * area * area / top), critical_discharge(b, s, h, g),
                    1e-10 * critical_discharge(b, s, h, g));
      }
}

TEST(OpenChannel, CriticalSectionStressByHand) {
  // Rectangle b = 4 m, h = 1.5 m: y = 1 m, V^2 = g y, R = 4/6 m:
  // tau = 1000 g n_s^2 g y / R^(1/3) with n_s = 0.016.
  const double expected = 1000.0 * g * 0.016 * 0.016 * g * 1.0 / std::cbrt(4.0 / 6.0);
  EXPECT_NEAR(critical_section_stress(4.0, 0.0, 1.5, 0.016, g), expected, 1e-10 * expected);
  EXPECT_EQ(critical_section_stress(4.0, 1.0, 0.0, 0.016, g), 0.0);
  EXPECT_EQ(critical_section_stress(0.0, 0.0, 1.0, 0.016, g), 0.0) << "no section, no flow";
  // Stress rises with head (V^2 ~ h, R^(1/3) grows slower).
  EXPECT_GT(critical_section_stress(4.0, 1.0, 2.0, 0.016, g), critical_section_stress(4.0, 1.0, 1.0, 0.016, g));
}

TEST(PipeFlow, DischargeAndWallStressByHand) {
  // d = 0.5 m, L = 40 m, h = 5 m, n_s = 0.016, K_e = 0.5: f = 8 g n_s^2 / (d/4)^(1/3) = 0.0401818,
  // Q = A sqrt(2 g h / (1 + K_e + f L / d)) = 0.196350 x 4.56157 = 0.895663 m^3/s.
  const double f = 8.0 * g * 0.016 * 0.016 / std::cbrt(0.125);
  EXPECT_NEAR(f, 0.0401818, 1e-7);
  const double q = pipe_discharge(0.5, 40.0, 5.0, 0.016, 0.5, g);
  EXPECT_NEAR(q, 0.895663, 1e-6);
  // Wall stress from the energy slope, rho g (d/4) h_f / L, equals the Darcy form rho f V^2 / 8.
  const double v = q / (std::numbers::pi * 0.0625), hf = f * (40.0 / 0.5) * v * v / (2.0 * g);
  EXPECT_NEAR(pipe_wall_stress(0.5, q, 0.016, g), 1000.0 * g * 0.125 * hf / 40.0, 1e-9);
  EXPECT_NEAR(pipe_wall_stress(0.5, q, 0.016, g), 1000.0 * f * v * v / 8.0, 1e-9);
  EXPECT_EQ(pipe_discharge(0.5, 40.0, -0.1, 0.016, 0.5, g), 0.0) << "level below the pipe's centre";
}

}  // namespace
