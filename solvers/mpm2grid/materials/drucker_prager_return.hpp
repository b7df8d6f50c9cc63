#pragma once
// The return mapping of HenckyDruckerPrager (materials/hencky_drucker_prager.hpp, where the
// model is described): project() and what it calls, defined in a header so that the particle
// update loop (model/simulation.cpp) inlines them per particle.
#include <algorithm>
#include <cmath>

#include "solvers/mpm2grid/materials/hencky_drucker_prager.hpp"
#include "solvers/mpm2grid/materials/log_stretch.hpp"

namespace suite::mpm2grid {

template <int Dim>
Matrix<Dim> HenckyDruckerPrager::hencky_stress(const Matrix<Dim>& log_v, double log_j) const {
  return 2 * mu * log_v + lambda * log_j * Matrix<Dim>::Identity();
}

template <int Dim>
Matrix<Dim> HenckyDruckerPrager::kirchhoff(const Matrix<Dim>& U, const Vector<Dim>& eps) const {
  const Vector<Dim> principal = (2 * mu * eps.array() + lambda * eps.sum()).matrix();
  return U * principal.asDiagonal() * U.transpose();
}

template <int Dim>
double HenckyDruckerPrager::inertial_yield(double q_trial, double p, double q_c, double dt) const {
  const InertialFriction& f = inertial;
  const double shear = std::sqrt(6.0) * mu;  // q per unit |dev eps|, Pa
  const double mu_s = std::tan(friction_angle);
  // I per unit Delta: sqrt(2) / dt  d / sqrt(p / rho_s).
  const double rate = std::sqrt(2.0) / dt * f.grain_diameter / std::sqrt(p / f.grain_density);
  // g(Delta) = q_tr - shear Delta - M(mu(I(Delta))) p - q_c, decreasing, g(0) > 0 >= g(hi).
  const auto g = [&](double delta, double& slope) {
    const double I = rate * delta;
    const double m = mu_s + (f.tan_limit - mu_s) * I / (f.inertial_number_0 + I);
    const double sine = m / std::sqrt(1 + m * m);  // sin(atan m)
    // dM/dDelta = dM/dsin dsin/dm dm/dI dI/dDelta.
    const double dm =
        (f.tan_limit - mu_s) * f.inertial_number_0 / ((f.inertial_number_0 + I) * (f.inertial_number_0 + I));
    const double dsine = 1 / ((1 + m * m) * std::sqrt(1 + m * m));
    const double dslope = Dim == 2 ? std::sqrt(3.0) : 18 / ((3 - sine) * (3 - sine));
    slope = -shear - dslope * dsine * dm * rate * p;
    return q_trial - shear * delta - slope_of_sine<Dim>(sine) * p - q_c;
  };
  double lo = 0, hi = (q_trial - friction_slope<Dim>() * p - q_c) / shear;  // hi: the static return's
  double delta = 0, slope = 0;
  for (int it = 0; it < 100; ++it) {
    const double value = g(delta, slope);
    if (value > 0)
      lo = delta;
    else
      hi = delta;
    if (std::abs(value) <= 1e-13 * q_trial || hi - lo <= 1e-15 * hi) break;
    const double next = delta - value / slope;  // Newton's step where it stays in the bracket
    delta = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return q_trial - shear * delta;
}

template <int Dim>
StrainReturn<Dim> HenckyDruckerPrager::return_strain(const Vector<Dim>& eps_trial, double saturation, double dt) const {
  const double K = bulk_modulus<Dim>();
  const double M = friction_slope<Dim>();
  const double q_c = cohesion_intercept<Dim>(saturation);
  const double tr = eps_trial.sum();
  const double p_trial = -K * tr;            // as invariants() gives it
  const double q_yield = M * p_trial + q_c;  // the cone's q at the trial pressure, Pa

  // Apex: the trial pressure lies beyond the cone's tip (tension larger than the cohesion
  // allows). Dev eps = 0 and p = -q_c / M, i.e. tr eps = q_c / (M K).
  if (M > 0 && q_yield <= 0) {
    const double tr_apex = q_c / (M * K);
    return {Vector<Dim>::Constant(tr_apex / Dim), ReturnCase::apex};
  }
  // Elastic where q_tr <= q_yield (here q_yield >= 0): tested as q_tr^2 = 6 mu^2 |dev eps|^2 <=
  // q_yield^2, without the square root that most particles (elastic) would wait for.
  const double mean = tr / Dim;
  const Vector<Dim> dev = eps_trial - mean * Vector<Dim>::Ones();
  if (6 * mu * mu * dev.squaredNorm() <= q_yield * q_yield) return {eps_trial, ReturnCase::elastic};

  // Cone: q_tr > q_yield >= 0, so q_tr > 0. Scale the deviator so that q = q_yield (with the
  // rate-dependent friction the larger q of the rate); the trace, hence p and the volume, stays
  // (zero dilatancy).
  const double q_trial = 2 * mu * std::sqrt(1.5) * dev.norm();  // as invariants() gives it
  const double q_new = inertial.on && dt > 0 && p_trial > 0 ? inertial_yield<Dim>(q_trial, p_trial, q_c, dt) : q_yield;
  return {(mean * Vector<Dim>::Ones() + (q_new / q_trial) * dev).eval(), ReturnCase::cone};
}

template <int Dim>
ReturnResult<Dim> HenckyDruckerPrager::project(const Matrix<Dim>& F_trial, double log_jp, double saturation,
                                               double dt) const {
  return project<Dim>(F_trial, stretch_spectrum<Dim>(F_trial), log_jp, saturation, dt);
}

template <int Dim, int N>
void HenckyDruckerPrager::project_all(const Matrix<Dim>* F_trial, const double* log_jp, const double* saturation,
                                      ReturnResult<Dim>* out, double dt) const {
  StretchSpectrum<Dim> s[N];
  stretch_spectra<Dim, N>(F_trial, s);
  // The strain tensors of all N, of which the elastic returns use theirs.
  Matrix<Dim> log_v[N];
  log_left_stretches<Dim, N>(s, log_v);
  for (int n = 0; n < N; ++n) out[n] = project<Dim>(F_trial[n], s[n], log_jp[n], saturation[n], dt, &log_v[n]);
}

template <int Dim>
ReturnResult<Dim> HenckyDruckerPrager::project(const Matrix<Dim>& F_trial, const StretchSpectrum<Dim>& s, double log_jp,
                                               double saturation, double dt, const Matrix<Dim>* log_v) const {
  const double shift = volume_correction ? log_jp : 0.0;  // log-volume added to the trial strain
  // An elastic return: U exp(eps + shift/Dim) V^T = exp(shift/Dim) F_trial, no round-off from U;
  // log_jp goes to 0 (the trace is kept) or through without the correction; the stress, where
  // F_E stays F_trial, from stress().
  const auto elastic = [&](auto&& stress) {
    ReturnResult<Dim> out;
    out.F = shift == 0 ? F_trial : (std::exp(shift / Dim) * F_trial).eval();
    out.log_jp = volume_correction ? 0.0 : log_jp;
    out.has_stress = shift == 0;
    if (out.has_stress) out.stress = stress();
    return out;
  };
  // The yield test needs the principal strains alone (s), and an elastic return's stress the
  // strain tensor from them (log_stretch.hpp): the principal directions only for a plastic one.
  if (s.accurate &&
      return_strain<Dim>((s.log_sigma.array() + shift / Dim).matrix(), saturation).kind == ReturnCase::elastic)
    return elastic([&] { return hencky_stress<Dim>(log_v ? *log_v : log_left_stretch<Dim>(s), s.log_sigma.sum()); });

  const LeftStretch<Dim> b = left_stretch<Dim>(F_trial);
  const Vector<Dim> eps = (b.log_sigma.array() + shift / Dim).matrix();
  const StrainReturn<Dim> r = return_strain<Dim>(eps, saturation, dt);
  // Elastic here where the closed form was not accurate or its strains were just outside the cone.
  if (r.kind == ReturnCase::elastic) return elastic([&] { return kirchhoff<Dim>(b.U, b.log_sigma); });

  ReturnResult<Dim> out;
  out.kind = r.kind;
  out.plastic_strain = (eps - r.eps).norm();
  // U exp(eps_new) V^T with V^T = diag(1 / sigma) U^T F_trial.
  const Vector<Dim> stretch = (r.eps - b.log_sigma).array().exp().matrix();
  out.F = b.U * stretch.asDiagonal() * b.U.transpose() * F_trial;
  // log_jp <- tr(eps shifted) - tr(eps new): exactly 0 for cone returns (trace kept), the removed
  // volume for the apex.
  if (!volume_correction)
    out.log_jp = log_jp;
  else if (r.kind == ReturnCase::apex)
    out.log_jp = eps.sum() - r.eps.sum();
  else
    out.log_jp = 0;
  return out;
}

}  // namespace suite::mpm2grid
