// Analytic seed shapes: implicit functions, volumes, ray hits and normals (see shapes.hpp).
#include "carving/render/shapes.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <vector>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

void require_positive(const char* shape, const char* what, double value) {
  if (!(value > 0) || !std::isfinite(value))
    throw InputError(fmt::format("{}: {} = {} mm; it must be a positive, finite length", shape, what, value));
}

// Smallest non-negative root pair of the ray p + t d against the unit sphere after dividing
// coordinates by `axes`: the interval [t0, t1] of the ray inside the ellipsoid, or nothing.
std::optional<std::array<double, 2>> ellipsoid_interval(const Eigen::Vector3d& axes, const Eigen::Vector3d& p,
                                                        const Eigen::Vector3d& d) {
  const Eigen::Vector3d q = p.cwiseQuotient(axes), e = d.cwiseQuotient(axes);
  const double A = e.squaredNorm(), B = q.dot(e), C = q.squaredNorm() - 1;
  const double disc = B * B - A * C;
  if (disc < 0) return std::nullopt;
  const double root = std::sqrt(disc);
  // Stable roots: avoid cancellation between -B and root.
  const double s = B >= 0 ? -B - root : -B + root;
  double t0 = s / A, t1 = s != 0 ? C / s : t0;
  if (t0 > t1) std::swap(t0, t1);
  if (t1 < 0) return std::nullopt;
  return std::array<double, 2>{t0, t1};
}

// A point within `tolerance` of the crossing of f between a and b (f(a) = fa > 0 >= fb = f(b)), on
// the inside side: the Illinois variant of regula falsi, with a bisection every fourth step so
// the bracket always shrinks.
template <class F>
double first_crossing(const F& f, double a, double fa, double b, double fb, double tolerance) {
  int side = 0;
  for (int iteration = 0; iteration < 300 && b - a > tolerance; ++iteration) {
    double c = iteration % 4 == 3 ? 0.5 * (a + b) : (a * fb - b * fa) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc <= 0) {
      b = c, fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c, fa = fc;
      if (side == +1) fb *= 0.5;
      side = +1;
    }
  }
  return b;
}

// First point of [t0, t1] where f <= 0: samples every `step` and refines the first sign change.
template <class F>
std::optional<double> sample_and_refine(const F& f, double t0, double t1, double step, double tolerance) {
  double previous = t0, f_previous = f(t0);
  if (f_previous <= 0) return t0;
  for (double t = t0 + step;; t += step) {
    const double tt = std::min(t, t1);
    if (const double value = f(tt); value <= 0)
      return first_crossing(f, previous, f_previous, tt, value, tolerance);
    else
      f_previous = value;
    if (tt >= t1) return std::nullopt;
    previous = tt;
  }
}

// A lower bound of a convex function on [lo, hi] from its values at lo < m1 < m2 < hi: outside
// [m1, m2] it lies above the secant through m1 and m2; inside, above both the secant through lo
// and m1 and the one through m2 and hi, extended.
double convex_lower_bound(double lo, double f_lo, double m1, double f1, double m2, double f2, double hi, double f_hi) {
  const double slope = (f2 - f1) / (m2 - m1);
  double bound = std::min({f1, f2, f1 - slope * (m1 - lo), f2 + slope * (hi - m2)});
  if (m1 > lo && hi > m2) {
    const double sa = (f1 - f_lo) / (m1 - lo), sb = (f_hi - f2) / (hi - m2);
    const auto above = [&](double t) { return std::max(f1 + sa * (t - m1), f2 + sb * (t - m2)); };
    double inner = std::min(above(m1), above(m2));
    if (sb != sa) {
      const double cross = (f2 - f1 + sa * m1 - sb * m2) / (sa - sb);
      if (cross > m1 && cross < m2) inner = std::min(inner, above(cross));
    }
    bound = std::min(bound, inner);
  }
  return bound;
}

// Gauss-Kronrod 7/15-point rule on [lo, hi] (QUADPACK qk15 nodes and weights).
struct Quadrature {
  double value = 0;
  double error = 0;
};

template <class F>
Quadrature gauss_kronrod_15(const F& f, double lo, double hi) {
  static constexpr std::array<double, 8> xgk = {
      0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
      0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
      0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
      0.207784955007898467600689403773245, 0.0};
  static constexpr std::array<double, 8> wgk = {
      0.022935322010529224963732008058970, 0.063092092629978553290700663189204, 0.104790010322250183839876322541518,
      0.140653259715525918745189590510238, 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
      0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static constexpr std::array<double, 4> wg = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                               0.381830050505118944950369775488975,
                                               0.417959183673469387755102040816327};
  const double centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double fc = f(centre);
  double kronrod = wgk[7] * fc, gauss = wg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double sum = f(centre - half * xgk[j]) + f(centre + half * xgk[j]);
    kronrod += wgk[j] * sum;
    if (j % 2 == 1) gauss += wg[j / 2] * sum;
  }
  return {kronrod * half, std::abs((kronrod - gauss) * half)};
}

// Globally adaptive Gauss-Kronrod: bisects the interval with the largest error estimate until the
// summed estimate is below `tolerance` or `max_intervals` is reached.
template <class F>
Quadrature integrate_adaptive(const F& f, double lo, double hi, double tolerance, int max_intervals = 4000) {
  struct Piece {
    double lo, hi;
    Quadrature q;
    bool operator<(const Piece& other) const { return q.error < other.q.error; }
  };
  std::priority_queue<Piece> pieces;
  Quadrature total = gauss_kronrod_15(f, lo, hi);
  pieces.push({lo, hi, total});
  int count = 1;
  while (total.error > tolerance && count < max_intervals) {
    const Piece worst = pieces.top();
    pieces.pop();
    const double mid = 0.5 * (worst.lo + worst.hi);
    const Quadrature left = gauss_kronrod_15(f, worst.lo, mid), right = gauss_kronrod_15(f, mid, worst.hi);
    total.value += left.value + right.value - worst.q.value;
    total.error += left.error + right.error - worst.q.error;
    pieces.push({worst.lo, mid, left});
    pieces.push({mid, worst.hi, right});
    ++count;
  }
  // Re-add the pieces to remove the drift of the running sums.
  total = {};
  while (!pieces.empty()) {
    total.value += pieces.top().q.value;
    total.error += pieces.top().q.error;
    pieces.pop();
  }
  return total;
}

}  // namespace

Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& axis, double angle) {
  if (!(axis.norm() > 0))
    throw InputError("rotation_matrix: the rotation axis is the zero vector; give a non-zero axis");
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------- Shape

Shape::Shape(const Pose& pose) : pose_(pose) {
  const Eigen::Matrix3d& R = pose.rotation;
  if (!R.allFinite() || !pose.centre.allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-9 ||
      R.determinant() < 0)
    throw InputError(
        fmt::format("shape pose: the rotation must be a proper rotation matrix (R^T R = I, det R = +1) "
                    "and the centre finite; got det R = {:.6g}, |R^T R - I| = {:.3g}",
                    R.determinant(), (R.transpose() * R - Eigen::Matrix3d::Identity()).norm()));
}

std::optional<double> Shape::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
  const double length = direction.norm();
  if (!(length > 0)) throw InputError("first_hit: the ray direction is the zero vector; give a non-zero direction");
  const Eigen::Matrix3d Rt = pose_.rotation.transpose();
  return local_first_hit(Rt * (origin - pose_.centre), Rt * (direction / length));
}

Eigen::Vector3d Shape::normal(const Eigen::Vector3d& X) const {
  return pose_.rotation * local_normal(to_body(X));
}

std::optional<double> Shape::local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  const double r = local_radius();
  const auto span = ellipsoid_interval(Eigen::Vector3d::Constant(r), p, d);
  if (!span) return std::nullopt;
  const auto f = [&](double t) { return local_implicit(p + t * d); };
  return sample_and_refine(f, std::max((*span)[0], 0.0), (*span)[1], sampling_step(), 1e-12 * r);
}

Eigen::Vector3d Shape::local_normal(const Eigen::Vector3d& p) const {
  const double h = 1e-6 * local_radius();
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[k] = h;
    g[k] = local_implicit(p + e) - local_implicit(p - e);
  }
  return g.norm() > 0 ? Eigen::Vector3d(g.normalized()) : Eigen::Vector3d(p.normalized());
}

// --------------------------------------------------------------------------------------- Sphere

Sphere::Sphere(double radius_mm, const Pose& pose) : Shape(pose), r_(radius_mm) {
  require_positive("Sphere", "radius", radius_mm);
}

double Sphere::volume() const {
  return 4.0 / 3.0 * std::numbers::pi * r_ * r_ * r_;
}

std::optional<double> Sphere::local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  const auto span = ellipsoid_interval(Eigen::Vector3d::Constant(r_), p, d);
  if (!span) return std::nullopt;
  return std::max((*span)[0], 0.0);
}

// ------------------------------------------------------------------------------------ Ellipsoid

Ellipsoid::Ellipsoid(double a, double b, double c, const Pose& pose) : Shape(pose), axes_(a, b, c) {
  require_positive("Ellipsoid", "a", a);
  require_positive("Ellipsoid", "b", b);
  require_positive("Ellipsoid", "c", c);
}

double Ellipsoid::volume() const {
  return 4.0 / 3.0 * std::numbers::pi * axes_.prod();
}

double Ellipsoid::local_implicit(const Eigen::Vector3d& p) const {
  return axes_.minCoeff() * (p.cwiseQuotient(axes_).norm() - 1);
}

std::optional<double> Ellipsoid::local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  const auto span = ellipsoid_interval(axes_, p, d);
  if (!span) return std::nullopt;
  return std::max((*span)[0], 0.0);
}

Eigen::Vector3d Ellipsoid::local_normal(const Eigen::Vector3d& p) const {
  return p.cwiseQuotient(axes_.cwiseProduct(axes_)).normalized();
}

// ------------------------------------------------------------------------------- Superellipsoid

Superellipsoid::Superellipsoid(double a, double b, double c, double e1, double e2, const Pose& pose)
    : Shape(pose), axes_(a, b, c), e1_(e1), e2_(e2) {
  require_positive("Superellipsoid", "a", a);
  require_positive("Superellipsoid", "b", b);
  require_positive("Superellipsoid", "c", c);
  for (const auto& [key, value] : {std::pair{"e1", e1}, std::pair{"e2", e2}})
    if (!(value >= 0.1 && value <= 4))
      throw InputError(
          fmt::format("Superellipsoid: exponent {} = {}; it must lie in [0.1, 4] (1 = ellipsoid)", key, value));
}

double Superellipsoid::volume() const {
  const auto beta = [](double x, double y) { return std::exp(std::lgamma(x) + std::lgamma(y) - std::lgamma(x + y)); };
  return 2 * axes_.prod() * e1_ * e2_ * beta(e1_ / 2 + 1, e1_) * beta(e2_ / 2, e2_ / 2);
}

double Superellipsoid::local_implicit(const Eigen::Vector3d& p) const {
  const double x = std::abs(p.x() / axes_.x()), y = std::abs(p.y() / axes_.y()), z = std::abs(p.z() / axes_.z());
  const double F = std::pow(std::pow(x, 2 / e2_) + std::pow(y, 2 / e2_), e2_ / e1_) + std::pow(z, 2 / e1_);
  return std::pow(F, e1_ / 2) - 1;
}

std::optional<double> Superellipsoid::local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  // Clip the ray to the bounding box |x| <= a, |y| <= b, |z| <= c (slab method).
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (std::abs(p[k]) > axes_[k]) return std::nullopt;
      continue;
    }
    double ta = (-axes_[k] - p[k]) / d[k], tb = (axes_[k] - p[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return std::nullopt;
  const auto f = [&](double t) { return local_implicit(p + t * d); };
  const double tolerance = 1e-12 * local_radius();
  if (e1_ > 2 || e2_ > 2) return sample_and_refine(f, t0, t1, sampling_step(), tolerance);
  if (f(t0) <= 0) return t0;
  // Convex: golden-section search for the minimum of f on [t0, t1]; the ray hits iff it is <= 0.
  // Stops early at the first point inside, or once the convexity lower bound below is positive.
  const double inv_phi = (std::sqrt(5.0) - 1) / 2;
  double lo = t0, hi = t1, f_lo = f(t0), f_hi = f(t1);
  if (f_lo <= 0) return t0;
  if (f_hi <= 0) return first_crossing(f, t0, f_lo, t1, f_hi, tolerance);
  double m1 = hi - inv_phi * (hi - lo), m2 = lo + inv_phi * (hi - lo);
  double f1 = f(m1), f2 = f(m2);
  while (f1 > 0 && f2 > 0) {
    if (hi - lo <= tolerance || convex_lower_bound(lo, f_lo, m1, f1, m2, f2, hi, f_hi) > 0) return std::nullopt;
    if (f1 < f2) {
      hi = m2, f_hi = f2, m2 = m1, f2 = f1;
      m1 = hi - inv_phi * (hi - lo), f1 = f(m1);
    } else {
      lo = m1, f_lo = f1, m1 = m2, f1 = f2;
      m2 = lo + inv_phi * (hi - lo), f2 = f(m2);
    }
  }
  // f(t0) > 0 >= f(inside) and f is convex: exactly one crossing in between.
  const double inside = f1 <= 0 ? m1 : m2;
  return first_crossing(f, t0, f(t0), inside, f1 <= 0 ? f1 : f2, tolerance);
}

// --------------------------------------------------------------------------------- CreasedGrain

CreasedGrain::CreasedGrain(double a, double b, double c, double crease_radius, double crease_depth, const Pose& pose,
                           double volume_tolerance)
    : Shape(pose), axes_(a, b, c), crease_radius_(crease_radius), crease_depth_(crease_depth) {
  require_positive("CreasedGrain", "a", a);
  require_positive("CreasedGrain", "b", b);
  require_positive("CreasedGrain", "c", c);
  require_positive("CreasedGrain", "crease_radius", crease_radius);
  if (!(crease_depth > 0 && crease_depth <= c))
    throw InputError(
        fmt::format("CreasedGrain: crease_depth = {} mm; it must lie in (0, c] = (0, {}]", crease_depth, c));
  if (!(volume_tolerance > 0))
    throw InputError(fmt::format("CreasedGrain: volume_tolerance = {}; it must be positive (mm^3)", volume_tolerance));
  crease_z_ = -c + crease_depth - crease_radius;

  // Groove volume: 4 x the quarter x >= 0, y >= 0 (the groove is symmetric in x and y).
  const double inner_tolerance = 1e-3 * volume_tolerance / a;  // mm^2, per x
  const double y_max = std::min(crease_radius, b);
  const auto area_at = [&](double x) {
    return integrate_adaptive([&](double y) { return groove_chord(x, y); }, 0.0, y_max, inner_tolerance).value;
  };
  const Quadrature outer = integrate_adaptive(area_at, 0.0, a, volume_tolerance / 8);
  volume_ = ellipsoid_volume() - 4 * outer.value;
  volume_error_ = 4 * (outer.error + a * inner_tolerance);
}

double CreasedGrain::ellipsoid_volume() const {
  return 4.0 / 3.0 * std::numbers::pi * axes_.prod();
}

double CreasedGrain::groove_chord(double x, double y) const {
  const double s2 = crease_radius_ * crease_radius_ - y * y;
  const double h2 = 1 - (x * x) / (axes_.x() * axes_.x()) - (y * y) / (axes_.y() * axes_.y());
  if (s2 <= 0 || h2 <= 0) return 0;
  const double h = axes_.z() * std::sqrt(h2);
  // The slot holds z < z_c + sqrt(r^2 - y^2) at this y; the body's chord is [-h, h].
  return std::clamp(crease_z_ + std::sqrt(s2) + h, 0.0, 2 * h);
}

double CreasedGrain::chord_length_z(double x, double y) const {
  const double h2 = 1 - (x * x) / (axes_.x() * axes_.x()) - (y * y) / (axes_.y() * axes_.y());
  if (h2 <= 0) return 0;
  return 2 * axes_.z() * std::sqrt(h2) - groove_chord(x, y);
}

double CreasedGrain::groove_distance(const Eigen::Vector3d& p) const {
  const double dz = p.z() - crease_z_;
  if (dz >= 0) return std::hypot(p.y(), dz) - crease_radius_;  // the round roof
  return std::abs(p.y()) - crease_radius_;                     // the straight walls
}

double CreasedGrain::local_implicit(const Eigen::Vector3d& p) const {
  const double ellipsoid = axes_.minCoeff() * (p.cwiseQuotient(axes_).norm() - 1);
  return std::max(ellipsoid, -groove_distance(p));
}

std::optional<double> CreasedGrain::local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  const auto span = ellipsoid_interval(axes_, p, d);
  if (!span) return std::nullopt;
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double r = crease_radius_, oy = p.y(), oz = p.z() - crease_z_;
  // The ray's open interval in the slot, the union of two convex sets whose union is convex:
  // the disc's cylinder y^2 + (z - z_c)^2 < r^2 and the half-slab |y| < r, z < z_c.
  double s0 = inf, s1 = -inf;
  const double A = d.y() * d.y() + d.z() * d.z(), B = oy * d.y() + oz * d.z(), C = oy * oy + oz * oz - r * r;
  if (A < 1e-300) {
    if (C < 0) s0 = -inf, s1 = inf;
  } else if (const double disc = B * B - A * C; disc > 0) {
    s0 = (-B - std::sqrt(disc)) / A, s1 = (-B + std::sqrt(disc)) / A;
  }
  double h0 = -inf, h1 = inf;  // half-slab
  if (d.y() == 0) {
    if (std::abs(oy) >= r) h0 = inf, h1 = -inf;
  } else {
    const double ta = (-r - oy) / d.y(), tb = (r - oy) / d.y();
    h0 = std::min(ta, tb), h1 = std::max(ta, tb);
  }
  if (d.z() == 0) {
    if (oz >= 0) h0 = inf, h1 = -inf;
  } else if (d.z() > 0) {
    h1 = std::min(h1, -oz / d.z());
  } else {
    h0 = std::max(h0, -oz / d.z());
  }
  if (h0 < h1) s0 = std::min(s0, h0), s1 = std::max(s1, h1);

  double t = std::max((*span)[0], 0.0);
  if (s0 < t && t < s1) t = s1;
  if (t > (*span)[1]) return std::nullopt;
  return t;
}

Eigen::Vector3d CreasedGrain::local_normal(const Eigen::Vector3d& p) const {
  const double ellipsoid = axes_.minCoeff() * (p.cwiseQuotient(axes_).norm() - 1);
  const double groove = groove_distance(p);
  if (std::abs(groove) < std::abs(ellipsoid)) {
    // Outward from the body is into the slot: towards its axis on the roof, towards y = 0 on the walls.
    const Eigen::Vector3d radial(0, p.y(), p.z() - crease_z_);
    if (radial.z() >= 0 && radial.norm() > 0) return -radial.normalized();
    return {0, p.y() > 0 ? -1.0 : 1.0, 0};
  }
  return p.cwiseQuotient(axes_.cwiseProduct(axes_)).normalized();
}

}  // namespace suite::carving
