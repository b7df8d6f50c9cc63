#include "demo/ritter/ritter_solution.hpp"

#include <cmath>

namespace suite::demo {

RitterSolution::RitterSolution(double h0, double gravity) : h0_(h0), g_(gravity), c0_(std::sqrt(gravity * h0)) {}

ShallowWaterState RitterSolution::at(double x, double t) const {
  if (t <= 0.0) return x < 0.0 ? ShallowWaterState{h0_, 0.0} : ShallowWaterState{};
  const double xi = x / t;
  if (xi <= -c0_) return {h0_, 0.0};
  if (xi >= 2.0 * c0_) return {};
  const double s = 2.0 * c0_ - xi;
  return {s * s / (9.0 * g_), 2.0 / 3.0 * (c0_ + xi)};
}

double RitterSolution::unit_discharge_at_dam() const {
  return 8.0 / 27.0 * std::sqrt(g_) * std::pow(h0_, 1.5);
}

}  // namespace suite::demo
