#include "solvers/mpm2grid/scenes/read_inlet.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/config/units.hpp"
#include "core/errors.hpp"

namespace suite::mpm2grid {
namespace {

// A hydrograph table of [time, discharge per metre] rows in the units of `columns`.
Hydrograph read_table(const config::Section& s) {
  const auto columns = s.get<std::vector<std::string>>("columns", {"s", "m^2/s"});
  if (columns.size() != 2) s.reject("columns", "give the units of the two columns, e.g. [s, m^2/s] or [min, m^2/s]");
  double to_s = 1, to_q = 1;
  try {
    to_s = units::convert(1.0, columns[0], "s");
    to_q = units::convert(1.0, columns[1], "m^2/s");
  } catch (const InputError& e) {
    s.reject("columns", fmt::format("{}; the first column is a time, the second a discharge per metre of width "
                                    "(m^2/s)",
                                    e.what()));
  }
  std::vector<double> t, q;
  for (const auto& row : s.table("rows", columns)) {
    t.push_back(row[0] * to_s);
    q.push_back(row[1] * to_q);
    const std::size_t n = t.size();
    if (q.back() < 0)
      s.reject("rows",
               fmt::format("row {} has a negative discharge ({} {}); give discharges >= 0", n, row[1], columns[1]));
    if (n > 1 && !(t[n - 1] > t[n - 2]))
      s.reject("rows", fmt::format("times must increase, but row {} ({} {}) does not come after row {}", n, row[0],
                                   columns[0], n - 1));
  }
  return Hydrograph::table(std::move(t), std::move(q));
}

}  // namespace

template <int Dim>
InletSettings<Dim> read_inlet(const config::Section& s, const Vec<Dim>& lo, const Vec<Dim>& hi, double spacing,
                              double density) {
  InletSettings<Dim> in;
  in.lo = lo, in.hi = hi, in.spacing = spacing, in.density = density;
  in.height = s.quantity("height", "m", config::Range::positive());
  if (lo[1] + in.height > hi[1] * (1 + 1e-12))
    s.reject("height", fmt::format("the inlet section [floor, floor + height] reaches y = {} m, above the domain's "
                                   "top at y = {} m; lower inlet.height or raise domain.hi",
                                   lo[1] + in.height, hi[1]));
  if (std::llround(in.height / spacing) < 1)
    s.reject("height", fmt::format("is under half a particle spacing ({} m = grid.spacing / particles_per_cell): no "
                                   "row of particles fits; raise it or refine grid.spacing",
                                   spacing));
  const bool velocity = s.has("velocity"), table = s.has("discharge");
  if (velocity == table)
    s.reject(velocity ? "discharge" : "velocity",
             "give exactly one of velocity: (constant inflow, m/s) or discharge: {columns, rows} (a hydrograph of "
             "discharge per metre of width)");
  if (velocity) {
    const double v = s.quantity("velocity", "m/s", config::Range::at_least(0));
    in.discharge = Hydrograph::constant(v * in.height);
  } else {
    in.discharge = read_table(s.section("discharge"));
  }
  return in;
}

template InletSettings<2> read_inlet<2>(const config::Section&, const Vec<2>&, const Vec<2>&, double, double);
template InletSettings<3> read_inlet<3>(const config::Section&, const Vec<3>&, const Vec<3>&, double, double);

}  // namespace suite::mpm2grid
