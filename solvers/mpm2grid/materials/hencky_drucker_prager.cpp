#include "solvers/mpm2grid/materials/hencky_drucker_prager.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "solvers/mpm2grid/materials/log_stretch.hpp"

namespace suite::mpm2grid {

namespace {

[[noreturn]] void reject(const char* key, double value, const char* valid) {
  std::ostringstream msg;
  msg.precision(17);
  msg << "soil material (Hencky Drucker-Prager): " << key << " = " << value << " is invalid: " << valid;
  throw InputError(msg.str());
}

}  // namespace

HenckyDruckerPrager HenckyDruckerPrager::from_young(double young, double poisson, double friction_angle,
                                                    double cohesion, bool volume_correction) {
  if (!(std::isfinite(young) && young > 0)) reject("young", young, "Young's modulus must be > 0 Pa");
  if (!(poisson > -1 && poisson < 0.5)) reject("poisson", poisson, "Poisson's ratio must lie in (-1, 0.5)");
  if (!(friction_angle >= 0 && friction_angle < std::numbers::pi / 2))
    reject("friction_angle", friction_angle, "the friction angle must lie in [0, pi/2) rad");
  if (!(std::isfinite(cohesion) && cohesion >= 0)) reject("cohesion", cohesion, "the cohesion must be >= 0 Pa");
  HenckyDruckerPrager m;
  m.mu = young / (2 * (1 + poisson));
  m.lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson));
  m.friction_angle = friction_angle;
  m.sin_friction = std::sin(friction_angle);
  m.cos_friction = std::cos(friction_angle);
  m.cohesion = cohesion;
  m.volume_correction = volume_correction;
  return m;
}

double HenckyDruckerPrager::cohesion_at(double saturation) const {
  return cohesion * (1 - std::clamp(saturation, 0.0, 1.0));
}

double HenckyDruckerPrager::p_wave_speed(double density) const {
  return std::sqrt((lambda + 2 * mu) / density);
}

template <int Dim>
Matrix<Dim> HenckyDruckerPrager::kirchhoff(const Matrix<Dim>& F_E) const {
  const StretchSpectrum<Dim> s = stretch_spectrum<Dim>(F_E);
  if (s.accurate && s.log_sigma.allFinite()) return hencky_stress<Dim>(log_left_stretch<Dim>(s), s.log_sigma.sum());
  const LeftStretch<Dim> b = left_stretch<Dim>(F_E);  // NaN for an inverted F, as the SVD gives
  return kirchhoff<Dim>(b.U, b.log_sigma);
}

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
Matrix<Dim> HenckyDruckerPrager::first_piola(const Matrix<Dim>& F_E) const {
  const RotationSvd<Dim> svd = rotation_svd<Dim>(F_E);
  const Vector<Dim> eps = svd.sigma.array().log().matrix();
  // dpsi/dsigma_i = (2 mu eps_i + lambda tr eps) / sigma_i, rotated back with U (.) V^T.
  const Vector<Dim> principal = ((2 * mu * eps.array() + lambda * eps.sum()) / svd.sigma.array()).matrix();
  return svd.U * principal.asDiagonal() * svd.V.transpose();
}

template <int Dim>
double HenckyDruckerPrager::energy_density(const Matrix<Dim>& F_E) const {
  const RotationSvd<Dim> svd = rotation_svd<Dim>(F_E);
  const Vector<Dim> eps = svd.sigma.array().log().matrix();
  const double tr = eps.sum();
  return mu * eps.squaredNorm() + 0.5 * lambda * tr * tr;
}

template <int Dim>
StressInvariants HenckyDruckerPrager::invariants(const Vector<Dim>& eps) const {
  const double tr = eps.sum();
  const Vector<Dim> dev = eps - (tr / Dim) * Vector<Dim>::Ones();
  return {-bulk_modulus<Dim>() * tr, 2 * mu * std::sqrt(1.5) * dev.norm()};
}

template <int Dim>
StrainReturn<Dim> HenckyDruckerPrager::return_strain(const Vector<Dim>& eps_trial, double saturation) const {
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

  // Cone: q_tr > q_yield >= 0, so q_tr > 0. Scale the deviator so that q = q_yield; the trace,
  // hence p and the volume, stays (zero dilatancy).
  const double q_trial = 2 * mu * std::sqrt(1.5) * dev.norm();  // as invariants() gives it
  return {(mean * Vector<Dim>::Ones() + (q_yield / q_trial) * dev).eval(), ReturnCase::cone};
}

template <int Dim>
ReturnResult<Dim> HenckyDruckerPrager::project(const Matrix<Dim>& F_trial, double log_jp, double saturation) const {
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
  // The yield test needs the principal strains alone, and an elastic return's stress the strain
  // tensor from them (log_stretch.hpp): the principal directions only for a plastic one.
  const StretchSpectrum<Dim> s = stretch_spectrum<Dim>(F_trial);
  if (s.accurate &&
      return_strain<Dim>((s.log_sigma.array() + shift / Dim).matrix(), saturation).kind == ReturnCase::elastic)
    return elastic([&] { return hencky_stress<Dim>(log_left_stretch<Dim>(s), s.log_sigma.sum()); });

  const LeftStretch<Dim> b = left_stretch<Dim>(F_trial);
  const Vector<Dim> eps = (b.log_sigma.array() + shift / Dim).matrix();
  const StrainReturn<Dim> r = return_strain<Dim>(eps, saturation);
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

#define SUITE_MPM2GRID_HDP_INSTANTIATE(D)                                                         \
  template Matrix<D> HenckyDruckerPrager::kirchhoff<D>(const Matrix<D>&) const;                   \
  template Matrix<D> HenckyDruckerPrager::first_piola<D>(const Matrix<D>&) const;                 \
  template double HenckyDruckerPrager::energy_density<D>(const Matrix<D>&) const;                 \
  template StressInvariants HenckyDruckerPrager::invariants<D>(const Vector<D>&) const;           \
  template StrainReturn<D> HenckyDruckerPrager::return_strain<D>(const Vector<D>&, double) const; \
  template ReturnResult<D> HenckyDruckerPrager::project<D>(const Matrix<D>&, double, double) const;
SUITE_MPM2GRID_HDP_INSTANTIATE(2)
SUITE_MPM2GRID_HDP_INSTANTIATE(3)
#undef SUITE_MPM2GRID_HDP_INSTANTIATE

}  // namespace suite::mpm2grid
