#pragma once
// The linear excess-stress erosion law of every stage (Partheniades 1965; Hanson & Cook 2004;
// Temple et al. 2005): erosion rate (m/s) = kd (tau_e - tau_c) for tau_e > tau_c, else 0,
// with kd in m^3/(N s) (1 cm^3/(N s) = 1e-6 m^3/(N s)) and stresses in Pa.
namespace suite::breach {

inline double erosion_rate(double kd, double stress, double critical_stress) {
  return stress > critical_stress ? kd * (stress - critical_stress) : 0.0;
}

}  // namespace suite::breach
