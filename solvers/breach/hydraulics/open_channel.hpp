#pragma once
// Open-channel relations for the flow over and through the embankment (docs/methods/breach.md). SI.
namespace suite::breach {

// Unit weight and density of water.
inline constexpr double kWaterDensity = 1000.0;  // kg/m^3

// Normal depth D (m) of a wide channel carrying q (m^2/s) on bed slope S (rise over run) with
// Manning n: q = (1/n) D^(5/3) S^(1/2) (Manning 1891; wide channel, hydraulic radius = D).
double normal_depth(double unit_discharge, double slope, double manning_n);

// Boundary stress of that flow, tau_0 = gamma_w D S (Pa), and the part acting on the soil
// grains, tau_e = tau_0 (n_s / n)^2 (the roughness partition of the SITES / WinDAM model,
// Temple et al. 1987, NRCS 1997 NEH 628 ch. 51, without vegetal cover).
double normal_flow_stress(double unit_discharge, double slope, double manning_n, double gravity);
double effective_stress(double boundary_stress, double grain_roughness, double manning_n);

// Critical depth (m) of a trapezoid (bottom b, side slopes s H:V) under energy head h: the depth
// y where y + A / (2 T) = h. It lies between 2h/3 (rectangle) and 4h/5 (triangle); Newton from
// inside that bracket, kept inside it, converges in a few iterations.
double critical_depth(double bottom_width, double side_slope, double head);

// Effective stress on the bed at the critical-flow control of the breach, from Manning's
// friction slope with the grain roughness: tau_e = gamma_w n_s^2 V^2 / R^(1/3), V = sqrt(g A / T)
// the critical velocity, R = A / P (the stress DL Breach and BREACH use at the control;
// Fread 1988, Wu 2013). 0 for h <= 0.
double critical_section_stress(double bottom_width, double side_slope, double head, double grain_roughness,
                               double gravity);

}  // namespace suite::breach
