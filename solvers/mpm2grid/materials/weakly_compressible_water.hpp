#pragma once
// Water: weakly compressible (Tait-type) equation of state (docs/methods/mpm2grid.md, "Water").
//
//   p(J) = k (J^-gamma - 1)                 pressure, Pa (compression positive)
//   sigma = -p I                            Cauchy stress, Pa
//   tau = J sigma = -J p I                  Kirchhoff stress, Pa (what P2G uses)
// J = V / V0 = rho0 / rho is the particle's volume ratio, k (Pa) a bulk-like stiffness and
// gamma (dimensionless, 7 by default) the exponent; the dissertation's p = k (1/J^gamma - 1) is
// the same thing.
//
// Stiffness and wave speed. dp/dJ = -gamma k J^-(gamma+1), so the effective bulk modulus at
// rest is K_eff = -J dp/dJ |_(J=1) = gamma k. With rho = rho0 / J,
//   dp/drho = gamma k rho^(gamma-1) / rho0^gamma,   which at rho = rho0 is gamma k / rho0,
// so the sound speed is c = sqrt(gamma k / rho0) (m/s, rho0 in kg/m^3). Weakly compressible
// codes choose k so that c is about ten times the fastest flow speed (density errors ~1%)
// rather than water's real K = 2.2 GPa, which would make the time step tiny.
//
// Tension clamp. The pressure used for the stress is max(p(J), min_pressure), min_pressure in
// Pa, <= 0. The default 0 lets water push but never pull: particles that drift apart at a free
// surface or in a splash (J > 1) carry no stress instead of attracting each other, which is
// what clusters particles (the tensile instability of particle methods). The cost: water that
// expanded keeps J > 1 until something compresses it again, so free-surface regions can hold
// a small volume excess. A negative min_pressure allows that much tension (e.g. -1e3 Pa);
// -infinity switches the clamp off (acoustics, the linear-wave tests).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"

namespace suite::mpm2grid {

struct WeaklyCompressibleWater {
  // A default-constructed model has k = 0 (no stiffness) and is not usable as is: set
  // bulk_modulus, or build with make().
  double bulk_modulus = 0;  // k, Pa
  double gamma = 7;         // exponent, dimensionless
  double min_pressure = 0;  // Pa, <= 0; -infinity for no clamp

  // Throws suite::InputError unless k > 0 and finite, gamma > 0 and finite, min_pressure <= 0
  // (-infinity allowed).
  static WeaklyCompressibleWater make(double bulk_modulus, double gamma = 7, double min_pressure = 0) {
    auto reject = [](const char* key, double value, const char* valid) {
      std::ostringstream msg;
      msg.precision(17);
      msg << "water (weakly compressible): " << key << " = " << value << " is invalid: " << valid;
      throw InputError(msg.str());
    };
    if (!(std::isfinite(bulk_modulus) && bulk_modulus > 0)) reject("bulk_modulus", bulk_modulus, "must be > 0 Pa");
    if (!(std::isfinite(gamma) && gamma > 0)) reject("gamma", gamma, "must be > 0");
    if (!(min_pressure <= 0)) reject("min_pressure", min_pressure, "must be <= 0 Pa (-inf: no tension clamp)");
    return {bulk_modulus, gamma, min_pressure};
  }

  // J^-gamma. For a whole gamma up to 16 (the usual 7) by repeated squaring and one division:
  // within (gamma + 1) / 2 ulp of pow (4 for 7) and cheaper (the pressure is taken once per
  // water particle and step, and pow showed in example 2's profile: docs/mpm2grid.md,
  // "Benchmarks"); pow otherwise.
  double inverse_power(double J) const {
    if (!(gamma <= 16 && gamma == std::floor(gamma))) return std::pow(J, -gamma);
    double result = 1, base = J;
    for (int e = static_cast<int>(gamma); e > 0; e >>= 1) {
      if (e & 1) result *= base;
      base *= base;
    }
    return 1 / result;
  }
  // k (J^-gamma - 1), Pa, without the clamp.
  double unclamped_pressure(double J) const { return bulk_modulus * (inverse_power(J) - 1); }
  // max(k (J^-gamma - 1), min_pressure), Pa: the pressure the stresses use.
  double pressure(double J) const { return std::max(unclamped_pressure(J), min_pressure); }
  // dp/dJ of the unclamped law, Pa: -gamma k J^-(gamma+1).
  double pressure_derivative(double J) const { return -gamma * bulk_modulus * std::pow(J, -gamma - 1); }
  // gamma k, Pa: the bulk modulus at J = 1.
  double effective_bulk_modulus() const { return gamma * bulk_modulus; }
  // sqrt(gamma k / rho0), m/s, rho0 the rest density in kg/m^3.
  double sound_speed(double density) const { return std::sqrt(gamma * bulk_modulus / density); }

  // Cauchy stress -p I, Pa.
  template <int Dim>
  Eigen::Matrix<double, Dim, Dim> cauchy(double J) const {
    return -pressure(J) * Eigen::Matrix<double, Dim, Dim>::Identity();
  }
  // Kirchhoff stress -J p I, Pa.
  template <int Dim>
  Eigen::Matrix<double, Dim, Dim> kirchhoff(double J) const {
    return -J * pressure(J) * Eigen::Matrix<double, Dim, Dim>::Identity();
  }
};

}  // namespace suite::mpm2grid
