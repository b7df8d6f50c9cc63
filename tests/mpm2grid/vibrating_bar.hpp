#pragma once
// The vibrating bar (docs/methods/mpm2grid.md, "Validation references") of test_vibrating_bar.cpp
// and test_implicit_forces.cpp: an elastic bar of length L = 1 m, fixed at x = 0 and free at
// x = L, four cells thick between slip walls, Poisson's ratio 0 (so that the 1D wave
// speed c = sqrt(E / rho) holds whatever the walls do laterally), kept elastic by a cohesion far
// above its stresses, and started in its first mode v(x, 0) = v0 sin(pi x / (2 L)): its
// centre-of-mass velocity is (2 / pi) v0 cos(omega t), omega = (pi / (2 L)) c.
#include <cmath>
#include <numbers>

#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid::vibrating_bar {

constexpr double kL = 1.0, kRho = 1000, kE = 1e6;  // m, kg/m^3, Pa
inline const double kC = std::sqrt(kE / kRho);     // m/s
inline const double kOmega = std::numbers::pi / (2 * kL) * kC;

// The scene at `cells` cells per bar length (cfl 0.4, no dt_max to speak of): in 2D a strip, in
// 3D a square duct, four cells across, with slip sides.
template <int Dim = 2>
SimulationSettings<Dim> settings(int cells) {
  const double h = kL / cells;
  SimulationSettings<Dim> s;
  s.h = h;
  s.walls.lo = Vec<Dim>::Zero();
  s.walls.hi = Vec<Dim>::Constant(4 * h);
  s.walls.hi[0] = 2 * kL;
  for (auto& sides : s.walls.kind) sides = {WallKind::slip, WallKind::slip};
  s.walls.kind[0] = {WallKind::sticky, WallKind::slip};
  s.soil.density = kRho;
  s.soil.material = HenckyDruckerPrager::from_young(kE, 0.0, 0.5, 1e9, false);
  s.buoyancy = false;
  s.cfl = 0.4;
  s.dt_max = 1;
  return s;
}

// The bar's particles (2 per cell and axis), in the first mode with amplitude v0 (m/s).
template <int Dim>
void seed(Particles<Dim>& soil, int cells, double v0) {
  const double spacing = kL / cells / 2, volume = std::pow(spacing, Dim);
  const int across = Dim == 2 ? 8 : 64;  // the lattice points of a cross-section: 8 per side
  for (int i = 0; i < 2 * cells; ++i)
    for (int j = 0; j < across; ++j) {
      Vec<Dim> x = Vec<Dim>::Constant(0.5 * spacing);
      x[0] += i * spacing;
      x[1] += (j % 8) * spacing;
      if constexpr (Dim == 3) x[2] += (j / 8) * spacing;
      Vec<Dim> v = Vec<Dim>::Zero();
      v[0] = v0 * std::sin(std::numbers::pi * x[0] / (2 * kL));
      soil.add(x, v, kRho * volume, volume);
    }
}

}  // namespace suite::mpm2grid::vibrating_bar
