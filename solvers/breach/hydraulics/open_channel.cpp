#include "solvers/breach/hydraulics/open_channel.hpp"

#include <algorithm>
#include <cmath>

namespace suite::breach {

double normal_depth(double q, double slope, double n) {
  if (q <= 0.0) return 0.0;
  return std::pow(q * n / std::sqrt(slope), 0.6);
}

double normal_flow_stress(double q, double slope, double n, double g) {
  return kWaterDensity * g * normal_depth(q, slope, n) * slope;
}

double effective_stress(double tau0, double ns, double n) {
  const double r = ns / n;
  return tau0 * r * r;
}

double critical_depth(double b, double s, double h) {
  if (h <= 0.0) return 0.0;
  if (s <= 0.0) return 2.0 * h / 3.0;
  const double lo = 2.0 * h / 3.0, hi = 0.8 * h;
  double y = 0.5 * (lo + hi);
  for (int i = 0; i < 30; ++i) {
    const double area = (b + s * y) * y, top = b + 2.0 * s * y;
    const double f = y + area / (2.0 * top) - h;
    const double df = 1.5 - area * s / (top * top);  // d/dy of y + A/(2T), since dA/dy = T
    const double next = std::clamp(y - f / df, lo, hi);
    if (std::abs(next - y) <= 1e-14 * h) return next;
    y = next;
  }
  return y;
}

double critical_section_stress(double b, double s, double h, double ns, double g) {
  if (h <= 0.0) return 0.0;
  const double y = critical_depth(b, s, h);
  const double area = (b + s * y) * y, top = b + 2.0 * s * y;
  if (area <= 0.0) return 0.0;
  const double wetted = b + 2.0 * y * std::sqrt(1.0 + s * s);
  const double v2 = g * area / top, radius = area / wetted;
  return kWaterDensity * g * ns * ns * v2 / std::cbrt(radius);
}

}  // namespace suite::breach
