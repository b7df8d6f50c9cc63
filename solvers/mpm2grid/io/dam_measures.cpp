#include "solvers/mpm2grid/io/dam_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace suite::mpm2grid {

template <int Dim>
long long count_within(const Particles<Dim>& P, const std::vector<Region>& regions, double margin) {
  long long n = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    n += !is_suspended(P.eroded[p]) && std::any_of(regions.begin(), regions.end(), [&](const Region& r) {
      return r.template contains<Dim>(P.x[p], margin);
    });
  return n;
}

template <int Dim>
SoilColumns soil_columns(const Particles<Dim>& soil, double x0, double y0, double h, long columns, long rows,
                         double particle_fill) {
  SoilColumns cells{
      x0, y0, h, columns, rows, particle_fill, std::vector<double>(static_cast<std::size_t>(columns * rows), 0.0)};
  for (std::size_t p = 0; p < soil.size(); ++p) {
    if (is_suspended(soil.eroded[p])) continue;
    const auto& x = soil.x[p];
    const auto c = static_cast<long>(std::floor((x[0] - x0) / h)), r = static_cast<long>(std::floor((x[1] - y0) / h));
    if (c >= 0 && c < columns && r >= 0 && r < rows) cells.count[static_cast<std::size_t>(c * rows + r)] += 1;
  }
  return cells;
}

std::vector<ColumnTop> crest_profile(const SoilColumns& cells) {
  std::vector<ColumnTop> profile;
  for (long c = 0; c < cells.columns; ++c) {
    const double* count = cells.count.data() + c * cells.rows;
    long r = 0;
    while (r < cells.rows && !(count[r] > 0)) ++r;
    if (r == cells.rows) continue;
    double top = cells.y0 + static_cast<double>(r) * cells.h;
    for (; r < cells.rows; ++r) {
      const double fill = count[r] * cells.particle_fill;
      top += std::min(fill, 1.0) * cells.h;
      if (fill <= 0.5) break;
    }
    profile.push_back({cells.x0 + (static_cast<double>(c) + 0.5) * cells.h, top});
  }
  return profile;
}

template <int Dim>
std::vector<ColumnTop> crest_profile(const Particles<Dim>& soil, double x0, double y0, double h, double particle_fill) {
  double right = x0, top = y0;
  for (const auto& x : soil.x) right = std::max(right, x[0]), top = std::max(top, x[1]);
  const auto columns = static_cast<long>(std::floor((right - x0) / h)) + 1;
  const auto rows = static_cast<long>(std::floor((top - y0) / h)) + 1;
  return crest_profile(soil_columns(soil, x0, y0, h, columns, rows, particle_fill));
}

double crest_height(const std::vector<ColumnTop>& profile, double floor) {
  if (profile.empty()) return std::numeric_limits<double>::quiet_NaN();
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& c : profile) top = std::max(top, c.top);
  return top - floor;
}

template long long count_within<2>(const Particles<2>&, const std::vector<Region>&, double);
template long long count_within<3>(const Particles<3>&, const std::vector<Region>&, double);
template SoilColumns soil_columns<2>(const Particles<2>&, double, double, double, long, long, double);
template SoilColumns soil_columns<3>(const Particles<3>&, double, double, double, long, long, double);
template std::vector<ColumnTop> crest_profile<2>(const Particles<2>&, double, double, double, double);
template std::vector<ColumnTop> crest_profile<3>(const Particles<3>&, double, double, double, double);

}  // namespace suite::mpm2grid
