#include "solvers/breach/hydrology/hydrograph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/config/units.hpp"
#include "core/errors.hpp"

namespace suite::breach {

namespace {
// The index i with t[i - 1] <= x < t[i], clamped to [1, n - 1].
std::size_t segment(const std::vector<double>& t, double x) {
  const auto i = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  return std::clamp<std::size_t>(i, 1, t.size() - 1);
}

// The piecewise-linear function through (t, q), held constant outside [t.front(), t.back()].
double interpolate(const std::vector<double>& t, const std::vector<double>& q, double x) {
  if (x <= t.front()) return q.front();
  if (x >= t.back()) return q.back();
  const std::size_t i = segment(t, x);
  const double w = (x - t[i - 1]) / (t[i] - t[i - 1]);
  return q[i - 1] + w * (q[i] - q[i - 1]);
}

}  // namespace

Hydrograph Hydrograph::table(std::vector<double> times, std::vector<double> discharges) {
  if (times.empty() || times.size() != discharges.size())
    throw InputError("an inflow table needs at least one row of [time, discharge]");
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (i > 0 && !(times[i] > times[i - 1]))
      throw InputError(
          fmt::format("inflow table: times must increase, but row {} ({} s) does not come after row {} ({} s)", i + 1,
                      times[i], i, times[i - 1]));
    if (discharges[i] < 0)
      throw InputError(fmt::format("inflow table: row {} has a negative discharge ({} m^3/s)", i + 1, discharges[i]));
  }
  Hydrograph h;
  h.kind_ = Kind::table;
  h.times_ = std::move(times);
  h.values_ = std::move(discharges);
  h.prefix_.assign(h.times_.size(), 0.0);
  for (std::size_t i = 1; i < h.times_.size(); ++i)
    h.prefix_[i] = h.prefix_[i - 1] + 0.5 * (h.values_[i - 1] + h.values_[i]) * (h.times_[i] - h.times_[i - 1]);
  return h;
}

Hydrograph Hydrograph::constant(double discharge) {
  Hydrograph h;
  h.kind_ = Kind::constant;
  h.peak_ = discharge;
  return h;
}

Hydrograph Hydrograph::sine(double peak, double period) {
  Hydrograph h;
  h.kind_ = Kind::sine;
  h.peak_ = peak;
  h.period_ = period;
  return h;
}

Hydrograph Hydrograph::triangular(double peak, double base, double time_to_peak, double duration) {
  Hydrograph h = table({0.0, time_to_peak, duration}, {base, peak, base});
  h.kind_ = Kind::triangular;
  return h;
}

Hydrograph Hydrograph::read_file(const std::filesystem::path& path, const std::string& time_unit,
                                 const std::string& discharge_unit) {
  const double ft = units::convert(1.0, time_unit, "s"), fq = units::convert(1.0, discharge_unit, "m^3/s");
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("cannot read the hydrograph file '{}'", path.string()));
  std::vector<double> t, q;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == ',' || c == ';' || c == '\t'; }, ' ');
    std::istringstream fields(line);
    std::string first;
    if (!(fields >> first) || first[0] == '#') continue;
    double a = 0.0, b = 0.0;
    const bool numeric = std::istringstream(first) >> a && fields >> b;
    if (!numeric) {
      if (t.empty()) continue;  // a header line
      throw InputError(fmt::format("{}:{}: expected two numbers (time in {}, discharge in {}), got '{}'", path.string(),
                                   number, time_unit, discharge_unit, line));
    }
    t.push_back(a * ft);
    q.push_back(b * fq);
  }
  try {
    return table(std::move(t), std::move(q));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path.string(), e.what()));
  }
}

Hydrograph Hydrograph::read(const config::Section& s) {
  using config::Range;
  const std::string type = s.choice("type", {"table", "constant", "sine", "triangular"});
  if (type == "table" && s.has("file")) {
    if (s.has("table")) s.reject("file", "give either a table or a file, not both");
    const auto columns = s.get<std::vector<std::string>>("columns", {"s", "m^3/s"});
    if (columns.size() != 2) s.reject("columns", "give the units of the two columns, e.g. [h, cfs]");
    const auto path = s.file("file");
    try {
      units::convert(1.0, columns[0], "s");
      units::convert(1.0, columns[1], "m^3/s");
    } catch (const InputError& e) {
      s.reject("columns", e.what());
    }
    return read_file(path, columns[0], columns[1]);
  }
  if (type == "table") {
    const auto rows = s.table("table", {"s", "m^3/s"});
    std::vector<double> t, q;
    for (const auto& r : rows) t.push_back(r[0]), q.push_back(r[1]);
    try {
      return table(std::move(t), std::move(q));
    } catch (const InputError& e) {
      s.reject("table", e.what());
    }
  }
  if (type == "constant") return constant(s.quantity("discharge", "m^3/s", Range::at_least(0)));
  if (type == "sine") {
    return sine(s.quantity("peak", "m^3/s", Range::at_least(0)), s.quantity("period", "s", 10.0, Range::positive()));
  }
  const double peak = s.quantity("peak", "m^3/s", Range::at_least(0));
  const double base = s.quantity("base", "m^3/s", 0.0, Range::between(0, peak));
  const double tp = s.quantity("time_to_peak", "s", Range::positive());
  const double duration = s.quantity("duration", "s", Range::positive());
  if (duration <= tp) s.reject("duration", fmt::format("must be longer than time_to_peak ({} s)", tp));
  return triangular(peak, base, tp, duration);
}

Hydrograph Hydrograph::with_peak(double peak) const {
  switch (kind_) {
    case Kind::constant:
      return constant(peak);
    case Kind::sine:
      return sine(peak, period_);
    case Kind::triangular:
      return triangular(peak, values_.front(), times_[1], times_[2]);
    case Kind::table:
      break;
  }
  throw InputError("an inflow table has no single peak to change; change its rows");
}

double Hydrograph::operator()(double t) const {
  switch (kind_) {
    case Kind::constant:
      return peak_;
    case Kind::sine:
      return peak_ * (0.5 + 0.5 * std::sin(2.0 * std::numbers::pi * t / period_));
    case Kind::table:
    case Kind::triangular:
      return interpolate(times_, values_, t);
  }
  return 0.0;
}

double Hydrograph::volume(double t0, double t1) const {
  return cumulative(t1) - cumulative(t0);
}

double Hydrograph::cumulative(double t) const {
  switch (kind_) {
    case Kind::constant:
      return peak_ * t;
    case Kind::sine: {
      const double w = 2.0 * std::numbers::pi / period_;
      return peak_ * (0.5 * t - 0.5 / w * (std::cos(w * t) - 1.0));
    }
    case Kind::table:
    case Kind::triangular:
      break;
  }
  // F(x) = integral from times_.front() to x of the constant-extended interpolant; F(t) - F(0).
  auto running = [&](double x) {
    if (x <= times_.front()) return values_.front() * (x - times_.front());
    if (x >= times_.back()) return prefix_.back() + values_.back() * (x - times_.back());
    const std::size_t i = segment(times_, x);
    return prefix_[i - 1] + 0.5 * (values_[i - 1] + interpolate(times_, values_, x)) * (x - times_[i - 1]);
  };
  return running(t) - running(0.0);
}

}  // namespace suite::breach
