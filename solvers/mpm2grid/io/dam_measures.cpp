#include "solvers/mpm2grid/io/dam_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace suite::mpm2grid {

template <int Dim>
double volume_within(const Particles<Dim>& P, const std::vector<Region>& regions, double margin) {
  double v = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    for (const auto& r : regions)
      if (r.template contains<Dim>(P.x[p], margin)) {
        v += P.volume0[p];
        break;
      }
  return v;
}

template <int Dim>
std::vector<ColumnTop> crest_profile(const Particles<Dim>& soil, double x0, double width, double half_spacing) {
  std::map<long long, double> highest;
  for (const auto& x : soil.x) {
    const auto c = static_cast<long long>(std::floor((x[0] - x0) / width));
    const auto [it, fresh] = highest.emplace(c, x[1]);
    if (!fresh) it->second = std::max(it->second, x[1]);
  }
  std::vector<ColumnTop> profile;
  profile.reserve(highest.size());
  for (const auto& [c, y] : highest) profile.push_back({x0 + (static_cast<double>(c) + 0.5) * width, y + half_spacing});
  return profile;
}

double crest_height(const std::vector<ColumnTop>& profile, double floor) {
  if (profile.empty()) return std::numeric_limits<double>::quiet_NaN();
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& c : profile) top = std::max(top, c.top);
  return top - floor;
}

template double volume_within<2>(const Particles<2>&, const std::vector<Region>&, double);
template double volume_within<3>(const Particles<3>&, const std::vector<Region>&, double);
template std::vector<ColumnTop> crest_profile<2>(const Particles<2>&, double, double, double);
template std::vector<ColumnTop> crest_profile<3>(const Particles<3>&, double, double, double);

}  // namespace suite::mpm2grid
