#pragma once
// The state a scene's particles start in: at rest and in equilibrium under gravity, built from
// the scene's regions (docs/mpm2grid.md, "Initial state"). Gravity acts along -y; each lattice
// point is loaded by what the lattice seeds above it in its column (x, and z in 3D, fixed):
//   water (free and pore water) at the hydrostatic pressure p = rho_w g (s - y), s the top of
//   the run of water-bearing lattice points the point is in (the top face of the run's highest
//   cell), or the scene's water.hydrostatic_surface when it gives one;
//   soil at the geostatic effective stress: vertical sigma'_v = g sum over the soil above of
//   (rho_d - (1 - n) rho_w [wet, with buoyancy]) times the layer thickness (half of its own
//   cell), horizontal K0 sigma'_v with K0 = 1 - sin(phi) unless the scene gives one; the
//   skeleton's F_E is the Hencky strain of that stress, through the return mapping, so that
//   the state is admissible.
// Units: Pa, m, kg/m^3.
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {

struct InitialPoint {
  double pressure = 0;            // water at the point (free or pore water), Pa
  double vertical_effective = 0;  // the soil's sigma'_v, Pa, compression positive
};

template <int Dim>
class InitialState {
 public:
  // The lattice of `scene` with points `spacing` apart (grid.spacing / particles_per_cell).
  InitialState(const Scene<Dim>& scene, double spacing);

  // The loads at the lattice point x, seeded as `at`: pressure 0 without water (or with
  // initial_state.hydrostatic off and no hydrostatic_surface), vertical_effective 0 without soil
  // (or with initial_state.geostatic off).
  InitialPoint at(const Vec<Dim>& x, const Seeded& at) const;

  // The water's J at pressure p: p(J) = p inverted, 1 at p = 0.
  double water_j(double pressure) const;

  // The elastic deformation gradient of a soil particle at (sigma'_v, K0 sigma'_v): diagonal,
  // with the principal Hencky strains of that Kirchhoff stress, returned onto the yield surface
  // with the cohesion of `saturation` if the stress lies outside it.
  Mat<Dim> soil_gradient(double vertical_effective, double saturation) const;

  double k0() const { return k0_; }

 private:
  const Scene<Dim>& scene_;
  double spacing_;
  double top_;  // the highest y any region reaches, m
  double k0_;
  double g_;  // |gravity|, m/s^2
};

}  // namespace suite::mpm2grid
