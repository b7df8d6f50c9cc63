#include "solvers/breach/hydrology/rating_curve.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.hpp"

namespace suite::breach {

RatingCurve RatingCurve::table(std::vector<double> levels, std::vector<double> discharges) {
  if (levels.size() < 2 || levels.size() != discharges.size())
    throw InputError("a spillway rating table needs at least two rows of [level, discharge]");
  if (discharges.front() != 0.0)
    throw InputError(fmt::format(
        "spillway rating table: the first row is the spillway crest and must have discharge 0, not {} m^3/s",
        discharges.front()));
  for (std::size_t i = 1; i < levels.size(); ++i)
    if (!(levels[i] > levels[i - 1]) || discharges[i] < discharges[i - 1])
      throw InputError(
          fmt::format("spillway rating table: levels must increase and discharges must not fall, but row {} "
                      "([{} m, {} m^3/s]) follows row {} ([{} m, {} m^3/s])",
                      i + 1, levels[i], discharges[i], i, levels[i - 1], discharges[i - 1]));
  RatingCurve r;
  r.levels_ = std::move(levels);
  r.discharges_ = std::move(discharges);
  return r;
}

RatingCurve RatingCurve::read(const config::Section& s) {
  const auto rows = s.table("table", {"m", "m^3/s"});
  std::vector<double> h, q;
  for (const auto& r : rows) h.push_back(r[0]), q.push_back(r[1]);
  try {
    return table(std::move(h), std::move(q));
  } catch (const InputError& e) {
    s.reject("table", e.what());
  }
}

double RatingCurve::operator()(double h) const {
  if (levels_.empty() || h <= levels_.front()) return 0.0;
  auto i = static_cast<std::size_t>(std::upper_bound(levels_.begin(), levels_.end(), h) - levels_.begin());
  i = std::min(i, levels_.size() - 1);
  const double w = (h - levels_[i - 1]) / (levels_[i] - levels_[i - 1]);
  return discharges_[i - 1] + w * (discharges_[i] - discharges_[i - 1]);
}

}  // namespace suite::breach
