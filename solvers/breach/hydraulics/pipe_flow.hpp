#pragma once
// Flow through an internal-erosion pipe in the embankment (WinDAM C's internal erosion mode,
// Hunt et al. 2021): a full circular pipe of diameter d and length L from the reservoir to the
// downstream face, discharging freely, driven by the head h of the reservoir above the pipe's
// centre:
//   Q = A sqrt(2 g h / (1 + K_e + f L / d)),  A = pi d^2 / 4   (energy equation with entrance
//   loss K_e and Darcy friction; Henderson 1966, ch. 2)
// with the friction factor from Manning's grain roughness, f = 8 g n_s^2 / R^(1/3), R = d / 4,
// so the wall stress tau = rho f V^2 / 8 = gamma_w n_s^2 V^2 / R^(1/3) is the same grain stress
// the breach's critical section uses. A pipe not yet submerged to its centre carries nothing.
namespace suite::breach {

double pipe_discharge(double diameter, double length, double head, double grain_roughness, double entrance_loss,
                      double gravity);
// Wall stress (Pa) of discharge Q in that pipe.
double pipe_wall_stress(double diameter, double discharge, double grain_roughness, double gravity);

}  // namespace suite::breach
