#pragma once
// The vibrating bar (docs/methods/mpm2grid.md, "Validation references") of test_vibrating_bar.cpp
// and test_implicit_forces.cpp: an elastic bar of length L = 1 m, fixed at x = 0 and free at
// x = L, in a strip of four cells between two slip walls, Poisson's ratio 0 (so that the 1D wave
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

// The scene at `cells` cells per bar length (cfl 0.4, no dt_max to speak of).
inline SimulationSettings<2> settings(int cells) {
  const double h = kL / cells;
  SimulationSettings<2> s;
  s.h = h;
  s.walls.lo = Vec<2>(0, 0), s.walls.hi = Vec<2>(2 * kL, 4 * h);
  s.walls.kind[0] = {WallKind::sticky, WallKind::slip};
  s.walls.kind[1] = {WallKind::slip, WallKind::slip};
  s.soil.density = kRho;
  s.soil.material = HenckyDruckerPrager::from_young(kE, 0.0, 0.5, 1e9, false);
  s.buoyancy = false;
  s.cfl = 0.4;
  s.dt_max = 1;
  return s;
}

// The bar's particles (2 per cell and axis), in the first mode with amplitude v0 (m/s).
inline void seed(Particles<2>& soil, int cells, double v0) {
  const double spacing = kL / cells / 2, volume = spacing * spacing;
  for (int i = 0; i < 2 * cells; ++i)
    for (int j = 0; j < 8; ++j) {
      const Vec<2> x((i + 0.5) * spacing, (j + 0.5) * spacing);
      soil.add(x, Vec<2>(v0 * std::sin(std::numbers::pi * x[0] / (2 * kL)), 0), kRho * volume, volume);
    }
}

}  // namespace suite::mpm2grid::vibrating_bar
