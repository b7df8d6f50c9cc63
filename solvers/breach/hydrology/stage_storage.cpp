#include "solvers/breach/hydrology/stage_storage.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace suite::breach {

StageStorage StageStorage::power_law(double alpha, double bottom, double exponent) {
  StageStorage s;
  s.alpha_ = alpha;
  s.bottom_ = bottom;
  s.exponent_ = exponent;
  return s;
}

StageStorage StageStorage::table(std::vector<double> levels, std::vector<double> volumes) {
  StageStorage s;
  s.is_table_ = true;
  s.table_ = PiecewiseLinear(std::move(levels), std::move(volumes),
                             {"stage-storage table", "level", "m", "volume", "m^3"},
                             PiecewiseLinear::Values::increasing);
  if (s.table_.y().front() < 0) throw InputError("stage-storage table: the first volume must be >= 0");
  return s;
}

StageStorage StageStorage::read(const config::Section& sec) {
  using config::Range;
  const std::string type = sec.choice("type", {"power_law", "table"});
  if (type == "power_law") {
    const double m = sec.number("exponent", 2.0, Range::between(1.0, 5.0));
    // alpha's unit depends on m (m^(3-m)); it is read as a plain number in SI.
    return power_law(sec.number("alpha", Range::positive()), sec.quantity("bottom", "m", 0.0), m);
  }
  return read_table_rows(sec, "table", "m", "m^3", &StageStorage::table);
}

double StageStorage::bottom() const {
  return is_table_ ? table_.x().front() - table_.y().front() / table_.slope(table_.x().front()) : bottom_;
}

// A table's storage: linear between rows, the last area continued above the last row, the first
// area continued below the first row down to zero storage.
double StageStorage::volume(double h) const {
  if (!is_table_) return h <= bottom_ ? 0.0 : alpha_ * std::pow(h - bottom_, exponent_);
  return std::max(0.0, table_.extended(h));
}

double StageStorage::area(double h) const {
  if (!is_table_) return h <= bottom_ ? 0.0 : alpha_ * exponent_ * std::pow(h - bottom_, exponent_ - 1.0);
  return table_.slope(h);
}

double StageStorage::level(double v) const {
  if (!is_table_) return v <= 0.0 ? bottom_ : bottom_ + std::pow(v / alpha_, 1.0 / exponent_);
  return table_.inverse(std::max(v, 0.0));
}

}  // namespace suite::breach
