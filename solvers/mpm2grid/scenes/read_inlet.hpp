#pragma once
// The scene's `inlet` section (boundary/inlet.hpp), water entering through the x_low side over
// [floor, floor + height], in one of two forms:
//
//   inlet: {height: 7.25 m, velocity: 2 m/s}          # constant: q = velocity * height
//   inlet:
//     height: 2.5 m
//     discharge:                                       # q(t) per metre of width, linear between rows,
//       columns: [s, m^2/s]                            # the first q before the first row, the last
//       rows: [[0, 0], [10, 12.5], [60, 12.5]]         # after the last; columns give the units
//
// InputError naming the key for a section above the domain's top, one under half a particle
// spacing, a negative velocity or discharge, times that do not increase.
#include "core/config/config.hpp"
#include "solvers/mpm2grid/boundary/inlet.hpp"

namespace suite::mpm2grid {

// lo, hi: the domain (m); spacing: the particle lattice spacing (m); density: the water's (kg/m^3).
template <int Dim>
InletSettings<Dim> read_inlet(const config::Section& inlet, const Vec<Dim>& lo, const Vec<Dim>& hi, double spacing,
                              double density);

}  // namespace suite::mpm2grid
