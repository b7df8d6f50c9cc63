#include "core/tables/piecewise_linear.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.hpp"

namespace suite {

PiecewiseLinear::PiecewiseLinear(std::vector<double> x, std::vector<double> y, const Names& n, Values values,
                                 std::size_t min_rows)
    : x_(std::move(x)), y_(std::move(y)) {
  if (x_.size() < min_rows || x_.size() != y_.size())
    throw InputError(fmt::format("the {} needs at least {} of [{}, {}]", n.table,
                                 min_rows == 1 ? std::string("one row") : fmt::format("{} rows", min_rows), n.x, n.y));
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const std::size_t row = i + 1;
    if (i > 0 && !(x_[i] > x_[i - 1]))
      throw InputError(fmt::format("{}: {}s must increase, but row {} ({} {}) does not come after row {} ({} {})",
                                   n.table, n.x, row, x_[i], n.x_unit, row - 1, x_[i - 1], n.x_unit));
    if (values == Values::nonnegative && y_[i] < 0)
      throw InputError(fmt::format("{}: row {} has a negative {} ({} {})", n.table, row, n.y, y_[i], n.y_unit));
    if (values == Values::nondecreasing && i > 0 && y_[i] < y_[i - 1])
      throw InputError(fmt::format("{}: {}s must not fall, but row {} ({} {}) is below row {} ({} {})", n.table, n.y,
                                   row, y_[i], n.y_unit, row - 1, y_[i - 1], n.y_unit));
    if (values == Values::increasing && i > 0 && !(y_[i] > y_[i - 1]))
      throw InputError(fmt::format("{}: {}s must increase, but row {} ({} {}) does not exceed row {} ({} {})", n.table,
                                   n.y, row, y_[i], n.y_unit, row - 1, y_[i - 1], n.y_unit));
  }
  prefix_.assign(x_.size(), 0.0);
  for (std::size_t i = 1; i < x_.size(); ++i)
    prefix_[i] = prefix_[i - 1] + 0.5 * (y_[i - 1] + y_[i]) * (x_[i] - x_[i - 1]);
}

std::size_t PiecewiseLinear::segment(double x) const {
  const auto i = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
  return std::clamp<std::size_t>(i, 1, x_.size() - 1);
}

double PiecewiseLinear::clamped(double x) const {
  if (x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  return extended(x);
}

double PiecewiseLinear::extended(double x) const {
  if (x < x_.front()) return y_.front() + slope(x) * (x - x_.front());
  if (x > x_.back()) return y_.back() + slope(x) * (x - x_.back());
  const std::size_t i = segment(x);
  const double w = (x - x_[i - 1]) / (x_[i] - x_[i - 1]);
  return y_[i - 1] + w * (y_[i] - y_[i - 1]);
}

double PiecewiseLinear::slope(double x) const {
  const std::size_t i = segment(x);
  return (y_[i] - y_[i - 1]) / (x_[i] - x_[i - 1]);
}

double PiecewiseLinear::inverse(double y) const {
  if (y < y_.front()) return x_.front() + (y - y_.front()) / slope(x_.front());
  if (y > y_.back()) return x_.back() + (y - y_.back()) / slope(x_.back());
  auto i = static_cast<std::size_t>(std::upper_bound(y_.begin(), y_.end(), y) - y_.begin());
  i = std::clamp<std::size_t>(i, 1, y_.size() - 1);
  return x_[i - 1] + (x_[i] - x_[i - 1]) * (y - y_[i - 1]) / (y_[i] - y_[i - 1]);
}

double PiecewiseLinear::integral(double x) const {
  if (x <= x_.front()) return y_.front() * (x - x_.front());
  if (x >= x_.back()) return prefix_.back() + y_.back() * (x - x_.back());
  const std::size_t i = segment(x);
  return prefix_[i - 1] + 0.5 * (y_[i - 1] + clamped(x)) * (x - x_[i - 1]);
}

}  // namespace suite
