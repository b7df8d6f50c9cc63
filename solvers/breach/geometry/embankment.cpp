#include "solvers/breach/geometry/embankment.hpp"

#include <algorithm>
#include <cmath>

namespace suite::breach {

Embankment Embankment::read(const config::Section& s) {
  using config::Range;
  Embankment e;
  e.height = s.quantity("height", "m", Range::positive());
  e.crest_width = s.quantity("crest_width", "m", Range::at_least(0));
  e.crest_length = s.quantity("crest_length", "m", Range::positive());
  // A slope of 0 H:V is a vertical face: no downstream face for the flow, no upstream toe.
  e.upstream_slope = s.number("upstream_slope", Range::positive());
  e.downstream_slope = s.number("downstream_slope", Range::positive());
  e.foundation = s.quantity("foundation", "m", 0.0);
  return e;
}

double Embankment::surface(double x) const {
  if (x <= 0.0) return foundation;
  if (x <= x_crest_downstream()) return foundation + x / downstream_slope;
  if (x <= x_crest_upstream()) return crest();
  return std::max(foundation, crest() - (x - x_crest_upstream()) / upstream_slope);
}

double Embankment::streamwise_length(double z) const {
  if (z > crest()) return 0.0;
  const double depth_below_crest = crest() - std::max(z, foundation);
  return crest_width + (upstream_slope + downstream_slope) * depth_below_crest;
}

double Embankment::downstream_face_length() const {
  return height * std::sqrt(1.0 + downstream_slope * downstream_slope);
}

double Embankment::cut_volume(double b, double s, double zb) const {
  // integral over u = z - z_b in [0, d] of min(b + 2 s u, L) (c0 - k u) du, with
  // c0 = streamwise_length(z_b), k = upstream_slope + downstream_slope, d = crest - z_b, L the
  // crest length: the cut's width stops at the abutments.
  const double d = std::max(0.0, crest() - std::max(zb, foundation));
  const double c0 = streamwise_length(crest() - d), k = upstream_slope + downstream_slope;
  // integral over [u0, u1] of (alpha + beta u)(c0 - k u) du
  auto linear_times_length = [&](double alpha, double beta, double u0, double u1) {
    auto f = [&](double u) {
      return alpha * c0 * u + (beta * c0 - alpha * k) * u * u / 2.0 - beta * k * u * u * u / 3.0;
    };
    return f(u1) - f(u0);
  };
  const double L = crest_length;
  if (b >= L) return linear_times_length(L, 0.0, 0.0, d);
  const double u_full = s > 0.0 ? (L - b) / (2.0 * s) : d;  // where the width reaches L
  if (u_full >= d) return linear_times_length(b, 2.0 * s, 0.0, d);
  return linear_times_length(b, 2.0 * s, 0.0, u_full) + linear_times_length(L, 0.0, u_full, d);
}

}  // namespace suite::breach
