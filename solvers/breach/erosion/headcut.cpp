#include "solvers/breach/erosion/headcut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/breach/erosion/excess_stress.hpp"
#include "solvers/breach/hydraulics/open_channel.hpp"
#include "solvers/breach/soil/soil.hpp"

namespace suite::breach {

namespace {

struct Jet {
  double tailwater = 0.0;   // y_t = y_c (m)
  double max_stress = 0.0;  // C_f rho U0^2 (Pa)
  double core = 0.0;        // J_p = C_d y0 (m)
};

Jet overfall_jet(double q, double drop, const HeadcutCoefficients& c, double g) {
  const double yc = std::cbrt(q * q / g);
  const double u0 = std::sqrt(g * yc + 2.0 * g * std::max(drop, 0.0));
  return {yc, c.jet_friction * kWaterDensity * u0 * u0, c.jet_diffusion * q / u0};
}

double stress_at(const Jet& jet, double depth) {
  return depth <= jet.core ? jet.max_stress : jet.max_stress * jet.core / depth;
}

// G(J) = (-uJ - ln(1 - uJ)) / u^2, an antiderivative of J / (1 - uJ) (its u -> 0 limit J^2/2 by
// the series where uJ is small, so there is no cancellation).
double antiderivative(double u, double J) {
  const double x = u * J;
  if (x < 1e-3) return J * J * (0.5 + x / 3.0 + x * x / 4.0 + x * x * x / 5.0);
  return (-x - std::log1p(-x)) / (u * u);
}

}  // namespace

double jet_stress(double q, double drop, double depth, const HeadcutCoefficients& c, double g) {
  if (q <= 0.0) return 0.0;
  return stress_at(overfall_jet(q, drop, c, g), depth);
}

double scour_time(double q, double drop, double d0, double d1, const Soil& soil, const HeadcutCoefficients& c,
                  double g) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (d1 <= d0) return 0.0;
  if (q <= 0.0 || soil.kd <= 0.0) return inf;
  const Jet jet = overfall_jet(q, drop, c, g);
  const double j0 = jet.tailwater + d0, j1 = jet.tailwater + d1;
  double t = 0.0;
  // Inside the potential core the stress, and so the rate, is constant.
  if (j0 < jet.core) {
    const double rate = erosion_rate(soil.kd, jet.max_stress, soil.tau_c);
    if (rate <= 0.0) return inf;
    t += (std::min(j1, jet.core) - j0) / rate;
  }
  const double a = std::max(j0, jet.core), b = j1;
  if (b > a) {
    // dJ/dt = kd (A/J - tau_c), A = tau_max J_p: t = (1/(kd A)) integral of J / (1 - uJ), u = tau_c / A.
    const double big_a = jet.max_stress * jet.core, u = soil.tau_c / big_a;
    if (u * b >= 1.0) return inf;  // equilibrium scour depth reached before d1
    t += (antiderivative(u, b) - antiderivative(u, a)) / (soil.kd * big_a);
  }
  return t;
}

double headcut_advance_rate(double q, double height, const Soil& soil, const HeadcutCoefficients& c, double g) {
  if (q <= 0.0 || soil.kd <= 0.0) return 0.0;
  const double base_rate = erosion_rate(soil.kd, jet_stress(q, height, std::cbrt(q * q / g), c, g), soil.tau_c);
  if (base_rate <= 0.0) return 0.0;
  const double critical_height = c.critical_height_factor * soil.s_u / soil.gamma_t;
  const double scour_needed = std::max(critical_height - height, 0.0);
  const double ts = scour_time(q, height, 0.0, scour_needed, soil, c, g);
  if (!std::isfinite(ts)) return 0.0;
  const double block = height + scour_needed;
  if (block <= 0.0) return base_rate;
  return block / (ts + block / base_rate);
}

}  // namespace suite::breach
