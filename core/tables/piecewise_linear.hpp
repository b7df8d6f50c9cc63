#pragma once
// A function given as a table of rows (x_i, y_i), linear between rows: inflow hydrographs Q(t),
// spillway ratings Q(H), stage-storage relations V(H). One type checks every such table the
// same way (x increasing; y non-negative, non-decreasing or increasing as the table needs) with
// an InputError that names the table, the row and both values, and answers the lookups the
// tables need: held at the end values or extended along the end segments outside the rows, the
// slope, the inverse, and the exact integral.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/config/config.hpp"
#include "core/errors.hpp"

namespace suite {

class PiecewiseLinear {
 public:
  // For messages: "spillway rating table", "level", "m", "discharge", "m^3/s". Plurals add "s".
  struct Names {
    std::string table, x, x_unit, y, y_unit;
  };
  enum class Values { nonnegative, nondecreasing, increasing };

  PiecewiseLinear() = default;
  // InputError naming the table and the first bad row: fewer than `min_rows` rows, x not
  // strictly increasing, or y breaking `values`.
  PiecewiseLinear(std::vector<double> x, std::vector<double> y, const Names& names, Values values,
                  std::size_t min_rows = 2);

  std::size_t rows() const { return x_.size(); }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }

  // y at x, held at the first and last y outside the rows.
  double clamped(double x) const;
  // y at x, the first and last segments continued outside the rows (needs two rows).
  double extended(double x) const;
  // dy/dx of the segment extended() uses at x (needs two rows).
  double slope(double x) const;
  // The x where extended() reaches y (needs increasing values).
  double inverse(double y) const;
  // The integral of clamped() from the first row's x to x (negative below it), exact.
  double integral(double x) const;

 private:
  std::size_t segment(double x) const;  // i with x_{i-1} <= x < x_i, clamped to [1, rows - 1]
  std::vector<double> x_, y_, prefix_;  // prefix_[i]: the integral from x_0 to x_i
};

// A scene's table `key`, rows [x, y] in the units given, made into a table by
// make(xs, ys); an InputError of make() is reported at the key (file, line, value).
template <class Make>
auto read_table_rows(const config::Section& s, const std::string& key, const std::string& x_unit,
                     const std::string& y_unit, Make&& make)
    -> decltype(make(std::vector<double>{}, std::vector<double>{})) {
  std::vector<double> x, y;
  for (const auto& row : s.table(key, {x_unit, y_unit})) x.push_back(row[0]), y.push_back(row[1]);
  try {
    return make(std::move(x), std::move(y));
  } catch (const InputError& e) {
    s.reject(key, e.what());
  }
}

}  // namespace suite
