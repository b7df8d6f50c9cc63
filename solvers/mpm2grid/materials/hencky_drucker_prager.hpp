#pragma once
// Soil: Hencky elasticity with Drucker-Prager plasticity whose cohesion drops with water
// saturation (docs/methods/mpm2grid.md, "Soil"; Klar et al. 2016, Tampubolon et al. 2017).
//
// Units: stresses, moduli and cohesion in Pa (N/m^2; Kirchhoff stress tau = J sigma also in Pa),
// energy density in J/m^3 of the reference volume, angles in radians, strains dimensionless.
// In 2D (plane strain) the same formulas hold with Dim = 2; every trace, deviator and norm runs
// over Dim dimensions.
//
// Elasticity. F_E = U diag(sigma) V^T with U, V rotations (materials/polar_svd.hpp), principal
// Hencky strain eps = log(sigma), and
//   psi = mu tr(eps^2) + lambda/2 (tr eps)^2               energy per reference volume, J/m^3
//   tau = U diag(2 mu eps + lambda tr(eps) 1) U^T         Kirchhoff stress, Pa
//   P   = dpsi/dF_E = tau F_E^-T = U diag((2 mu eps_i + lambda tr eps) / sigma_i) V^T   Pa
// tau is linear in eps, so the return mapping below is exact (no iteration). kirchhoff() and
// project() need only U and sigma, which left_stretch() (materials/polar_svd.hpp) gives faster
// than a full SVD in 3D (from F F^T = U diag(sigma^2) U^T), and V^T = diag(1/sigma) U^T F. An
// elastic state's tau = 2 mu log V + lambda tr(eps) I needs not even U: log V comes from the
// eigenvalues of F F^T alone (materials/log_stretch.hpp), and only plastic returns (and 3D
// states with a middle stretch under a tenth of the largest) find U.
//
// Plasticity (compression positive). With bulk modulus K = lambda + 2 mu / Dim and
//   p = -K tr(eps)                       pressure, Pa  (= -tr(tau) / Dim)
//   q = 2 mu sqrt(3/2) |dev eps|         equivalent shear stress, Pa  (= sqrt(3/2) |dev tau|)
// the admissible states are q <= M p + q_c, a cone in (p, q) with, in 3D,
//   M   = 6 sin(phi_f) / (3 - sin(phi_f))          (dimensionless slope)
//   q_c = 6 c cos(phi_f) / (3 - sin(phi_f))        (Pa, the cone's q at p = 0)
// (the cone through the compression corners of Mohr-Coulomb with friction angle phi_f and
// cohesion c), and in 2D
//   M   = sqrt(3) sin(phi_f),   q_c = sqrt(3) c cos(phi_f)
// which is Mohr-Coulomb in the plane exactly: with two principal stresses q = (sqrt(3)/2)
// |s1 - s2| and p = (s1 + s2)/2, so q <= M p + q_c reads |s1 - s2| / 2 <= p sin(phi_f) +
// c cos(phi_f). (The 3D constants in 2D would give sin(phi_2D) = M / sqrt(3): a scene's 30 deg
// would stand as 43.9 deg, and slopes showed it.) The cone's tip (apex) is at p = -q_c / M,
// i.e. tr(eps) = q_c / (M K) >= 0.
// Return mapping of a trial strain (non-associative, zero dilatancy):
//   apex     if M p_tr + q_c <= 0: eps = (q_c / (M K Dim)) 1, the tip (c = 0: eps = 0, F_E a
//            rotation, tau = 0: separated grains carry no stress);
//   elastic  if q_tr <= M p_tr + q_c: unchanged;
//   cone     otherwise: dev eps scaled by (M p_tr + q_c) / q_tr, tr(eps) kept (volume unchanged),
//            so q = M p_tr + q_c exactly.
// With phi_f = 0 (M = 0) there is no apex: the surface is the cylinder q <= q_c (pressure-
// independent), and a cohesionless, frictionless soil keeps only its volumetric response.
//
// Rate-dependent friction (optional, `inertial`): the mu(I) rheology of dense granular flow
// (GDR MiDi 2004, Eur. Phys. J. E 14, 341; Jop, Forterre & Pouliquen 2006, Nature 441, 727):
//   mu(I) = mu_s + (mu_2 - mu_s) I / (I_0 + I),   I = gamma_p d / sqrt(p / rho_s)
// with mu_s = tan(phi_f), mu_2 = tan(phi_2), gamma_p the plastic shear rate (1/s), d the grain
// diameter (m), rho_s the grains' density (kg/m^3). The cone's slope at a return is M of the
// angle atan(mu(I)) (the same M(phi) as above), so slow flow and rest keep phi_f and fast flow
// at low pressure (thin, sheared layers) approaches phi_2. The return is elastic when q_tr <=
// M(phi_f) p + q_c, as without it; otherwise the deviator is scaled to q_new, the root of
//   q_tr - sqrt(6) mu_G Delta = M(atan mu(I(Delta))) p + q_c,   I(Delta) = sqrt(2) (Delta / dt)
//   d / sqrt(p / rho_s)
// (Delta = |dev eps_tr| - |dev eps_new|, the deviatoric Hencky strain the return removes in
// the step dt; sqrt(2) |dev eps| is the shear strain gamma in simple shear), found by Newton's
// method safeguarded by bisection. At p <= 0 (cohesive soil in tension) and with dt = 0 (a
// static return, the initial state's) the static cone applies.
//
// Cohesion. c(S) = c0 (1 - clamp(S, 0, 1)): dry soil (S = 0) has the full cohesion c0, fully
// saturated soil (S = 1) none.
//
// Volume correction (Tampubolon et al. 2017, ACM Trans. Graph. 36(4) 105; the
// Klar et al. 2016 / Ziran "logJp" family; docs/methods/mpm2grid.md). Each particle carries log_jp
// (dimensionless, the log of a volume ratio). In project():
//   1. the trial strain is shifted isotropically before the yield test:
//        eps_tr <- log(sigma(F_trial)) + (log_jp / Dim) 1;
//   2. after the return, log_jp <- tr(eps_tr shifted) - tr(eps_new), which is
//        0                            after an elastic or cone return (the shift is absorbed
//                                     into F_E: elastic F_E = exp(log_jp / Dim) F_trial),
//        log_jp + log det F_trial - tr(eps_apex)   after an apex return (the volume the apex
//                                     projection removed from F_E is stored).
// Invariant (the caller forms F_trial = (I + dt grad v) F_E^n and stores the returned F and
// log_jp): log det F_E + log_jp grows by exactly log det F_trial - log det F_E^n each step,
// i.e. by the change of log det F of the total deformation F = F_E F_P. Starting from
// F_E = F, log_jp = 0 it therefore keeps
//        log_jp = log det F - log det F_E = log det F_P        (plastic volume change)
// and log_jp >= 0, with log_jp = 0 whenever the particle is not at the apex. Meaning: sand
// loosens (gains volume without stress) only while it is pulled apart (at the apex); when it
// is compressed again it first gives back that stored volume and only then resists, from its
// original density, so stretch/compress cycles do not ratchet its volume up. Without the
// correction (volume_correction = false, log_jp passed through unchanged) every apex projection
// leaves its volume in F_P for good: pulled-apart then re-compressed sand ends up larger at the
// same stress.
#include <algorithm>
#include <cmath>

#include "solvers/mpm2grid/materials/polar_svd.hpp"

namespace suite::mpm2grid {

enum class ReturnCase { elastic, cone, apex };

inline const char* to_string(ReturnCase c) {
  switch (c) {
    case ReturnCase::elastic:
      return "elastic";
    case ReturnCase::cone:
      return "cone";
    case ReturnCase::apex:
      return "apex";
  }
  return "?";
}

// Result of the return mapping in principal strains.
template <int Dim>
struct StrainReturn {
  Vector<Dim> eps;  // returned principal Hencky strain
  ReturnCase kind = ReturnCase::elastic;
};

// Result of project().
template <int Dim>
struct ReturnResult {
  Matrix<Dim> F;                          // projected elastic deformation gradient F_E
  double log_jp = 0;                      // new volume-correction state (see header comment)
  ReturnCase kind = ReturnCase::elastic;  // which branch of the return mapping was taken
  double plastic_strain = 0;              // |eps_tr - eps_new| (Frobenius, log strain) removed
  // kirchhoff(F), when project() had it at hand: an elastic return without a volume shift keeps
  // F = F_trial, whose stretches it has computed anyway (has_stress false otherwise).
  bool has_stress = false;
  Matrix<Dim> stress = Matrix<Dim>::Zero();
};

// Pressure p (compression positive) and equivalent shear stress q, both Pa.
struct StressInvariants {
  double p = 0;
  double q = 0;
};

// p = -tr(tau) / Dim, q = sqrt(3/2) |dev tau| of a Kirchhoff stress (Pa). For Hencky these are
// the same p, q as the return mapping uses, computed from the stress instead of the strain.
template <int Dim>
StressInvariants kirchhoff_invariants(const Matrix<Dim>& tau) {
  const double mean = tau.trace() / Dim;
  const Matrix<Dim> dev = tau - mean * Matrix<Dim>::Identity();
  return {-mean, std::sqrt(1.5) * dev.norm()};
}

template <int Dim>
struct StretchSpectrum;  // materials/log_stretch.hpp

// The mu(I) parameters (see "Rate-dependent friction" above); `on` false: rate-independent.
struct InertialFriction {
  bool on = false;
  double tan_limit = 0;          // mu_2 = tan(phi_2), > mu_s
  double inertial_number_0 = 0;  // I_0, > 0
  double grain_diameter = 0;     // d, m
  double grain_density = 0;      // rho_s, kg/m^3
};

struct HenckyDruckerPrager {
  // A default-constructed material has zero stiffness and is not usable as is: build real
  // ones with from_young().
  double mu = 0;              // shear modulus, Pa
  double lambda = 0;          // first Lame parameter, Pa
  double friction_angle = 0;  // phi_f, rad, in [0, pi/2)
  double sin_friction = 0;    // sin(phi_f) and cos(phi_f), set with it by from_young() (the
  double cos_friction = 1;    // return mapping needs them for every particle and step)
  double cohesion = 0;        // c0 of dry soil, Pa (stress-space form, see q_c above)
  bool volume_correction = true;
  InertialFriction inertial;  // rate-dependent friction, off by default

  // mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)). Throws suite::InputError
  // unless E > 0, -1 < nu < 0.5, 0 <= phi_f < pi/2, c0 >= 0 (all finite).
  static HenckyDruckerPrager from_young(double young, double poisson, double friction_angle, double cohesion,
                                        bool volume_correction = true);

  // K = lambda + 2 mu / Dim, Pa.
  template <int Dim>
  double bulk_modulus() const {
    return lambda + 2.0 * mu / Dim;
  }
  // M: 6 sin(phi_f) / (3 - sin(phi_f)) in 3D, sqrt(3) sin(phi_f) in 2D; dimensionless.
  template <int Dim>
  double friction_slope() const {
    return slope_of_sine<Dim>(sin_friction);
  }
  // M of a friction angle given by its sine s.
  template <int Dim>
  static double slope_of_sine(double s) {
    return Dim == 2 ? std::sqrt(3.0) * s : 6 * s / (3 - s);
  }
  // Turns the rate-dependent friction on: phi_2 (rad, in (phi_f, pi/2)), I_0 > 0, d > 0 (m),
  // rho_s > 0 (kg/m^3). Throws suite::InputError naming the parameter otherwise.
  void set_inertial_friction(double limit_angle, double inertial_number_0, double grain_diameter, double grain_density);
  // c(S) = c0 (1 - clamp(S, 0, 1)), Pa.
  double cohesion_at(double saturation) const { return cohesion * (1 - std::clamp(saturation, 0.0, 1.0)); }
  // q_c(S): 6 c(S) cos(phi_f) / (3 - sin(phi_f)) in 3D, sqrt(3) c(S) cos(phi_f) in 2D; Pa.
  template <int Dim>
  double cohesion_intercept(double saturation) const {
    const double c = cohesion_at(saturation) * cos_friction;
    return Dim == 2 ? std::sqrt(3.0) * c : 6 * c / (3 - sin_friction);
  }
  // P-wave speed sqrt((lambda + 2 mu) / rho), m/s, rho in kg/m^3: the fastest elastic wave,
  // for the time-step limit.
  double p_wave_speed(double density) const;

  // Kirchhoff stress tau (Pa) of an elastic deformation gradient with det F_E > 0.
  template <int Dim>
  Matrix<Dim> kirchhoff(const Matrix<Dim>& F_E) const;
  // First Piola-Kirchhoff stress P = dpsi/dF_E = tau F_E^-T (Pa).
  template <int Dim>
  Matrix<Dim> first_piola(const Matrix<Dim>& F_E) const;
  // Energy density psi (J/m^3 of reference volume).
  template <int Dim>
  double energy_density(const Matrix<Dim>& F_E) const;

  // p and q (Pa) of a principal Hencky strain.
  template <int Dim>
  StressInvariants invariants(const Vector<Dim>& eps) const;
  // The return mapping on principal strains (no volume correction): apex, elastic or cone. dt
  // (s) is the step the trial strain was made in, for the rate-dependent friction (0: static).
  template <int Dim>
  StrainReturn<Dim> return_strain(const Vector<Dim>& eps_trial, double saturation, double dt = 0) const;
  // The cone return's equivalent shear stress q_new (Pa) under the rate-dependent friction:
  // trial q_tr > M(phi_f) p + q_c, pressure p > 0, dt > 0 (see "Rate-dependent friction").
  template <int Dim>
  double inertial_yield(double q_trial, double p, double q_c, double dt) const;
  // The full plastic step of one particle: principal stretches of the trial F_E (left_stretch),
  // volume-correction shift, return mapping with the cohesion of `saturation`, F_E = U
  // exp(eps_new) V^T, new log_jp. An elastic return gives back F_trial itself (times
  // exp(log_jp / Dim) when the volume correction has something stored), with no round-off.
  // dt as in return_strain().
  template <int Dim>
  ReturnResult<Dim> project(const Matrix<Dim>& F_trial, double log_jp, double saturation, double dt = 0) const;
  // project() of N particles at once, out[n] as project(F_trial[n], log_jp[n], saturation[n], dt)
  // alone: their spectra computed together (stretch_spectra in log_stretch.hpp), whose chains of
  // dependent operations then overlap (with N = 4 and log V staged too: docs/mpm2grid.md, "Benchmarks").
  template <int Dim, int N>
  void project_all(const Matrix<Dim>* F_trial, const double* log_jp, const double* saturation, ReturnResult<Dim>* out,
                   double dt = 0) const;

 private:
  // project() given the spectrum s of F_trial (and its log V, when known).
  template <int Dim>
  ReturnResult<Dim> project(const Matrix<Dim>& F_trial, const StretchSpectrum<Dim>& s, double log_jp, double saturation,
                            double dt, const Matrix<Dim>* log_v = nullptr) const;
  // Kirchhoff stress 2 mu log V + lambda log J I of a Hencky strain tensor log V, log J = tr log V.
  template <int Dim>
  Matrix<Dim> hencky_stress(const Matrix<Dim>& log_v, double log_j) const;
  // Kirchhoff stress of principal Hencky strains eps along the columns of U.
  template <int Dim>
  Matrix<Dim> kirchhoff(const Matrix<Dim>& U, const Vector<Dim>& eps) const;
};

// The dry cohesion c0 (Pa) of the stress-space cone above equivalent to a strain-space cohesion
// c_C (dimensionless), the form of Klar et al. 2016 / Tampubolon et al. 2017 that the source
// dissertation's Table 3.4 gives (0.002 - 0.01). That form tests the trial strain shifted by
// (c_C / (Dim alpha)) 1, alpha = sqrt(2/3) 2 sin(phi_f) / (3 - sin(phi_f)) (Klar et al. 2016,
// ACM Trans. Graph. 35(4) 103), against the cohesionless cone, whose apex is at tr(eps) = 0: the shifted
// cone's apex is at the tensile volumetric log strain tr(eps) = c_C / alpha. The cone above has
// its apex at tr(eps) = q_c / (M K) = c0 / (K tan(phi_f)); equal apexes give
//   c0 = K tan(phi_f) c_C / alpha      (K the bulk modulus, Pa; phi_f > 0).
// (q_c / M = c0 / tan(phi_f) in 2D and 3D alike.)
// In 3D the two cones also share their slope in (p, q) (Klar's alpha gives exactly M), so they
// are the same surface; in 2D Klar's cone is flatter (slope 2/3 of M), and the mapping matches
// the apex, i.e. the tension the dry soil holds, while the friction stays Mohr-Coulomb's M.
inline double cohesion_of_strain_shift(double c_C, double bulk_modulus, double friction_angle) {
  const double s = std::sin(friction_angle);
  const double alpha = std::sqrt(2.0 / 3.0) * 2.0 * s / (3.0 - s);
  return bulk_modulus * std::tan(friction_angle) * c_C / alpha;
}

// kirchhoff(F_E), first_piola(), energy_density() and invariants() are defined, and
// instantiated for Dim = 2 and 3, in hencky_drucker_prager.cpp (link it); return_strain(),
// project() and the private stress helpers in materials/drucker_prager_return.hpp (include it to
// call them).

}  // namespace suite::mpm2grid
