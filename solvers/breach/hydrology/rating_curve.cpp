#include "solvers/breach/hydrology/rating_curve.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace suite::breach {

RatingCurve RatingCurve::table(std::vector<double> levels, std::vector<double> discharges) {
  RatingCurve r;
  r.table_ = PiecewiseLinear(std::move(levels), std::move(discharges),
                             {"spillway rating table", "level", "m", "discharge", "m^3/s"},
                             PiecewiseLinear::Values::nondecreasing);
  if (r.table_.y().front() != 0.0)
    throw InputError(fmt::format(
        "spillway rating table: the first row is the spillway crest and must have discharge 0, not {} m^3/s",
        r.table_.y().front()));
  return r;
}

RatingCurve RatingCurve::read(const config::Section& s) {
  return read_table_rows(s, "table", "m", "m^3/s", &RatingCurve::table);
}

double RatingCurve::operator()(double h) const {
  if (empty() || h <= crest()) return 0.0;
  return table_.extended(h);
}

}  // namespace suite::breach
