#include "solvers/mpm2grid/materials/hencky_drucker_prager.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "solvers/mpm2grid/materials/drucker_prager_return.hpp"
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

void HenckyDruckerPrager::set_inertial_friction(double limit_angle, double inertial_number_0, double grain_diameter,
                                                double grain_density) {
  if (!(limit_angle > friction_angle && limit_angle < std::numbers::pi / 2))
    reject("friction_angle_2", limit_angle, "the limit friction angle phi_2 must lie in (friction_angle, pi/2) rad");
  if (!(std::isfinite(inertial_number_0) && inertial_number_0 > 0))
    reject("inertial_number_0", inertial_number_0, "I_0 must be > 0");
  if (!(std::isfinite(grain_diameter) && grain_diameter > 0))
    reject("grain_diameter", grain_diameter, "the grain diameter must be > 0 m");
  if (!(std::isfinite(grain_density) && grain_density > 0))
    reject("grain_density", grain_density, "the grains' density must be > 0 kg/m^3");
  inertial = {true, std::tan(limit_angle), inertial_number_0, grain_diameter, grain_density};
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

#define SUITE_MPM2GRID_HDP_INSTANTIATE(D)                                         \
  template Matrix<D> HenckyDruckerPrager::kirchhoff<D>(const Matrix<D>&) const;   \
  template Matrix<D> HenckyDruckerPrager::first_piola<D>(const Matrix<D>&) const; \
  template double HenckyDruckerPrager::energy_density<D>(const Matrix<D>&) const; \
  template StressInvariants HenckyDruckerPrager::invariants<D>(const Vector<D>&) const;
SUITE_MPM2GRID_HDP_INSTANTIATE(2)
SUITE_MPM2GRID_HDP_INSTANTIATE(3)
#undef SUITE_MPM2GRID_HDP_INSTANTIATE

}  // namespace suite::mpm2grid
