#pragma once
// Reservoir stage-storage relation: volume V(H) stored below water level H and the surface
// area A(H) = dV/dH used by level-pool routing, A dH/dt = Q_in - Q_out (docs/methods/breach.md).
// Levels in m (same datum as the dam), volumes in m^3, areas in m^2.
//
//   power law: V = alpha (H - z0)^m for H >= z0 (alpha in m^(3-m), m >= 1; m = 1 is a
//              vertical-walled basin of area alpha, m = 3 a cone-like valley)
//   table:     (H, V) rows with H and V increasing; V linear between rows, so A is constant
//              between rows; above the last row the last area continues (vertical walls), and
//              below the first row the first area continues down to zero storage (a table that
//              starts at a spillway crest with storage below it still has a bottom)
// Scene form (section `reservoir.storage`):
//   type: power_law            type: table
//   alpha: 12000 m^2 ...       table: [[0 m, 0 m^3], [4 m, 2e5 m^3], [8 m, 9e5 m^3]]
//   exponent: 2
//   bottom: 0 m
#include <vector>

#include "core/config/config.hpp"
#include "core/tables/piecewise_linear.hpp"

namespace suite::breach {

class StageStorage {
 public:
  static StageStorage power_law(double alpha, double bottom, double exponent);
  static StageStorage table(std::vector<double> levels, std::vector<double> volumes);  // InputError if bad
  static StageStorage read(const config::Section& section);

  double volume(double level) const;  // m^3 (0 below the bottom)
  double area(double level) const;    // m^2
  double level(double volume) const;  // m, the inverse of volume()
  double bottom() const;              // m, level of zero storage
  // The power law's parameters (meaningless for a table).
  bool is_power_law() const { return !is_table_; }
  double alpha() const { return alpha_; }
  double exponent() const { return exponent_; }

 private:
  bool is_table_ = false;
  double alpha_ = 0.0, bottom_ = 0.0, exponent_ = 1.0;
  PiecewiseLinear table_;  // (level, volume)
};

}  // namespace suite::breach
