// The headcut advance law (solvers/breach/erosion/headcut.hpp): plane-jet stress, the closed-form
// scour time against numerical quadrature, and the limits of the advance rate.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solvers/breach/erosion/excess_stress.hpp"
#include "solvers/breach/erosion/headcut.hpp"
#include "solvers/breach/soil/soil.hpp"

namespace {

using namespace suite::breach;
constexpr double g = 9.81;

Soil soil(double kd_cm3, double tau_c, double s_u, double gamma = 19000.0) {
  Soil s;
  s.kd = kd_cm3 * 1e-6;
  s.tau_c = tau_c;
  s.s_u = s_u;
  s.gamma_t = gamma;
  s.grain_roughness = 0.016;
  return s;
}

TEST(Headcut, ExcessStressLaw) {
  EXPECT_DOUBLE_EQ(erosion_rate(2e-5, 10.0, 4.0), 2e-5 * 6.0);
  EXPECT_EQ(erosion_rate(2e-5, 3.0, 4.0), 0.0);
  EXPECT_EQ(erosion_rate(2e-5, 4.0, 4.0), 0.0);
}

TEST(Headcut, PlaneJetStressByHand) {
  // q = 2 m^2/s over a 5 m drop: y_c = (4/g)^(1/3), U0^2 = g y_c + 2 g 5, y0 = q / U0.
  const HeadcutCoefficients c;
  const double yc = std::cbrt(4.0 / g), u0 = std::sqrt(g * yc + 2.0 * g * 5.0), core = 2.6 * 2.0 / u0;
  const double tmax = 0.025 * 1000.0 * u0 * u0;
  EXPECT_NEAR(jet_stress(2.0, 5.0, 0.5 * core, c, g), tmax, 1e-9 * tmax);
  EXPECT_NEAR(jet_stress(2.0, 5.0, core, c, g), tmax, 1e-9 * tmax) << "continuous at the end of the core";
  EXPECT_NEAR(jet_stress(2.0, 5.0, 4.0 * core, c, g), tmax / 4.0, 1e-9 * tmax) << "decays as 1/J";
  EXPECT_EQ(jet_stress(0.0, 5.0, 1.0, c, g), 0.0);
}

// Simpson's rule on 1 / (kd (tau_j(J) - tau_c)) over the scour depth (smooth on each side of
// the core boundary, so both pieces are integrated separately).
double scour_time_by_quadrature(double q, double drop, double d0, double d1, const Soil& s,
                                const HeadcutCoefficients& c) {
  const double yc = std::cbrt(q * q / g), core = c.jet_diffusion * q / std::sqrt(g * yc + 2 * g * drop);
  auto inv_rate = [&](double d) { return 1.0 / erosion_rate(s.kd, jet_stress(q, drop, yc + d, c, g), s.tau_c); };
  auto simpson = [&](double a, double b) {
    if (b <= a) return 0.0;
    const int n = 20000;
    const double h = (b - a) / n;
    double sum = inv_rate(a) + inv_rate(b);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * inv_rate(a + i * h);
    return sum * h / 3.0;
  };
  const double split = std::clamp(core - yc, d0, d1);
  return simpson(d0, split) + simpson(split, d1);
}

TEST(Headcut, ScourTimeClosedFormAgainstQuadrature) {
  const HeadcutCoefficients c;
  for (double tau_c : {0.0, 0.05, 5.0, 40.0}) {  // 0.05 Pa: u J < 1e-3, the series branch
    const Soil s = soil(10.0, tau_c, 5000.0);
    for (auto [q, drop, d1] : {std::tuple{0.5, 2.0, 0.8}, std::tuple{2.0, 8.0, 3.0}, std::tuple{0.05, 1.0, 0.3}}) {
      const double exact = scour_time(q, drop, 0.0, d1, s, c, g);
      ASSERT_TRUE(std::isfinite(exact)) << q << " " << drop << " " << tau_c;
      EXPECT_NEAR(exact, scour_time_by_quadrature(q, drop, 0.0, d1, s, c), 1e-7 * exact)
          << "q " << q << " drop " << drop << " tau_c " << tau_c;
    }
  }
}

TEST(Headcut, ScourStopsAtTheEquilibriumDepth) {
  // Equilibrium where tau_j = tau_c: J_eq = tau_max J_p / tau_c. Below it finite, beyond it never.
  const HeadcutCoefficients c;
  const Soil s = soil(10.0, 50.0, 5000.0);
  const double q = 0.3, drop = 1.0, yc = std::cbrt(q * q / g), u0 = std::sqrt(g * yc + 2 * g * drop);
  const double j_eq = 0.025 * 1000 * u0 * u0 * (2.6 * q / u0) / 50.0;
  EXPECT_TRUE(std::isfinite(scour_time(q, drop, 0.0, 0.99 * (j_eq - yc), s, c, g)));
  EXPECT_FALSE(std::isfinite(scour_time(q, drop, 0.0, 1.01 * (j_eq - yc), s, c, g)));
}

TEST(Headcut, AdvanceRateLimits) {
  const HeadcutCoefficients c;
  const double q = 1.0;
  // A face taller than the critical height N s_u / gamma fails as fast as the jet undercuts it.
  const Soil weak = soil(20.0, 2.0, 3000.0);  // H_c = 3.85 x 3000 / 19000 = 0.61 m
  const double h = 4.0, yc = std::cbrt(q * q / g);
  EXPECT_NEAR(headcut_advance_rate(q, h, weak, c, g), 20e-6 * (jet_stress(q, h, yc, c, g) - 2.0), 1e-15);
  // A strong soil needs scour first: slower, and continuous where the face height reaches H_c.
  const Soil strong = soil(20.0, 2.0, 30000.0);  // H_c = 6.08 m
  const double hc = 3.85 * 30000.0 / 19000.0;
  EXPECT_LT(headcut_advance_rate(q, 3.0, strong, c, g), headcut_advance_rate(q, 3.0, weak, c, g));
  EXPECT_NEAR(headcut_advance_rate(q, hc * (1 - 1e-9), strong, c, g), headcut_advance_rate(q, hc, strong, c, g),
              1e-6 * headcut_advance_rate(q, hc, strong, c, g));
  // One cycle by hand: block H_c wide, scour time to H_c - H, then undercutting at the base rate.
  const double base = 20e-6 * (jet_stress(q, 3.0, yc, c, g) - 2.0);
  const double cycle = scour_time(q, 3.0, 0.0, hc - 3.0, strong, c, g) + hc / base;
  EXPECT_NEAR(headcut_advance_rate(q, 3.0, strong, c, g), hc / cycle, 1e-12);
  // Stalls when the jet cannot scour deep enough before its stress falls to tau_c.
  EXPECT_EQ(headcut_advance_rate(0.05, 0.5, soil(20.0, 60.0, 30000.0), c, g), 0.0);
  EXPECT_EQ(headcut_advance_rate(0.0, 3.0, weak, c, g), 0.0);
}

}  // namespace
