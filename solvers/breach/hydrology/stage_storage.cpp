#include "solvers/breach/hydrology/stage_storage.hpp"

#include <fmt/format.h>

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
  if (levels.size() < 2 || levels.size() != volumes.size())
    throw InputError("a stage-storage table needs at least two rows of [level, volume]");
  for (std::size_t i = 1; i < levels.size(); ++i) {
    if (!(levels[i] > levels[i - 1]) || !(volumes[i] > volumes[i - 1]))
      throw InputError(
          fmt::format("stage-storage table: levels and volumes must both increase, but row {} "
                      "([{} m, {} m^3]) does not exceed row {} ([{} m, {} m^3])",
                      i + 1, levels[i], volumes[i], i, levels[i - 1], volumes[i - 1]));
  }
  if (volumes.front() < 0) throw InputError("stage-storage table: the first volume must be >= 0");
  StageStorage s;
  s.is_table_ = true;
  s.levels_ = std::move(levels);
  s.volumes_ = std::move(volumes);
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
  const auto rows = sec.table("table", {"m", "m^3"});
  std::vector<double> h, v;
  for (const auto& r : rows) h.push_back(r[0]), v.push_back(r[1]);
  try {
    return table(std::move(h), std::move(v));
  } catch (const InputError& e) {
    sec.reject("table", e.what());
  }
}

double StageStorage::bottom() const {
  return is_table_ ? levels_.front() - volumes_.front() / area(levels_.front()) : bottom_;
}

double StageStorage::volume(double h) const {
  if (!is_table_) return h <= bottom_ ? 0.0 : alpha_ * std::pow(h - bottom_, exponent_);
  if (h <= levels_.front()) return std::max(0.0, volumes_.front() - area(h) * (levels_.front() - h));
  if (h >= levels_.back()) return volumes_.back() + area(h) * (h - levels_.back());
  const auto i = static_cast<std::size_t>(std::upper_bound(levels_.begin(), levels_.end(), h) - levels_.begin());
  return volumes_[i - 1] + (volumes_[i] - volumes_[i - 1]) * (h - levels_[i - 1]) / (levels_[i] - levels_[i - 1]);
}

double StageStorage::area(double h) const {
  if (!is_table_) return h <= bottom_ ? 0.0 : alpha_ * exponent_ * std::pow(h - bottom_, exponent_ - 1.0);
  std::size_t i = static_cast<std::size_t>(std::upper_bound(levels_.begin(), levels_.end(), h) - levels_.begin());
  i = std::clamp<std::size_t>(i, 1, levels_.size() - 1);
  return (volumes_[i] - volumes_[i - 1]) / (levels_[i] - levels_[i - 1]);
}

double StageStorage::level(double v) const {
  if (!is_table_) return v <= 0.0 ? bottom_ : bottom_ + std::pow(v / alpha_, 1.0 / exponent_);
  if (v <= volumes_.front()) return levels_.front() - (volumes_.front() - std::max(v, 0.0)) / area(levels_.front());
  if (v >= volumes_.back()) return levels_.back() + (v - volumes_.back()) / area(levels_.back());
  const auto i = static_cast<std::size_t>(std::upper_bound(volumes_.begin(), volumes_.end(), v) - volumes_.begin());
  return levels_[i - 1] + (levels_[i] - levels_[i - 1]) * (v - volumes_[i - 1]) / (volumes_[i] - volumes_[i - 1]);
}

}  // namespace suite::breach
