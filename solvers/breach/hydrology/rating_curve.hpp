#pragma once
// Outflow of a fixed structure (a principal or auxiliary spillway) against reservoir level:
// Q(H) linear between (level, discharge) rows, 0 at and below the first row, the last segment's
// slope continued above the last row. Scene form (section `reservoir.spillway`):
//   table: [[10 m, 0 m^3/s], [11 m, 20 m^3/s], [12 m, 60 m^3/s]]
#include <vector>

#include "core/config/config.hpp"
#include "core/tables/piecewise_linear.hpp"

namespace suite::breach {

class RatingCurve {
 public:
  RatingCurve() = default;                                                               // no spillway: Q = 0
  static RatingCurve table(std::vector<double> levels, std::vector<double> discharges);  // InputError if bad
  static RatingCurve read(const config::Section& section);

  double operator()(double level) const;  // m^3/s
  bool empty() const { return table_.rows() == 0; }
  double crest() const { return table_.x().front(); }  // the level where the outflow starts

 private:
  PiecewiseLinear table_;  // (level, discharge)
};

}  // namespace suite::breach
