#include "solvers/breach/hydraulics/weir.hpp"

#include <cmath>

namespace suite::breach {

double weir_discharge(double b, double s, double h, double g) {
  if (h <= 0.0) return 0.0;
  const double c1 = std::pow(2.0 / 3.0, 1.5) * std::sqrt(g);
  const double c2 = std::pow(4.0 / 5.0, 2.5) * std::sqrt(g / 2.0);
  return c1 * b * std::pow(h, 1.5) + c2 * s * std::pow(h, 2.5);
}

double critical_discharge(double b, double s, double h, double g) {
  if (h <= 0.0 || (b <= 0.0 && s <= 0.0)) return 0.0;
  auto energy_minus_head = [&](double y) {
    const double area = b * y + s * y * y, top = b + 2.0 * s * y;
    return y + area / (2.0 * top) - h;
  };
  // y + A/(2T) rises monotonically from 0 (at y = 0) past h (at y = h): bisection brackets it.
  double lo = 0.0, hi = h;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * h; ++i) {
    const double mid = 0.5 * (lo + hi);
    (energy_minus_head(mid) < 0.0 ? lo : hi) = mid;
  }
  const double y = 0.5 * (lo + hi);
  const double area = b * y + s * y * y, top = b + 2.0 * s * y;
  return std::sqrt(g * area * area * area / top);
}

}  // namespace suite::breach
