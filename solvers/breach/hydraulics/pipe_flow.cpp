#include "solvers/breach/hydraulics/pipe_flow.hpp"

#include <cmath>
#include <numbers>

#include "solvers/breach/hydraulics/open_channel.hpp"

namespace suite::breach {

double pipe_discharge(double d, double length, double head, double ns, double ke, double g) {
  if (head <= 0.0 || d <= 0.0) return 0.0;
  const double f = 8.0 * g * ns * ns / std::cbrt(d / 4.0);
  const double area = std::numbers::pi * d * d / 4.0;
  return area * std::sqrt(2.0 * g * head / (1.0 + ke + f * length / d));
}

double pipe_wall_stress(double d, double q, double ns, double g) {
  if (d <= 0.0 || q <= 0.0) return 0.0;
  const double v = q / (std::numbers::pi * d * d / 4.0);
  return kWaterDensity * g * ns * ns * v * v / std::cbrt(d / 4.0);
}

}  // namespace suite::breach
