#include "core/tables/hydrograph.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/config/units.hpp"
#include "core/errors.hpp"

namespace suite {

Hydrograph Hydrograph::table(std::vector<double> times, std::vector<double> discharges) {
  Hydrograph h;
  h.kind_ = Kind::table;
  h.table_ =
      PiecewiseLinear(std::move(times), std::move(discharges), {"inflow table", "time", "s", "discharge", "m^3/s"},
                      PiecewiseLinear::Values::nonnegative, 1);
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
  if (type == "table") return read_table_rows(s, "table", "s", "m^3/s", &Hydrograph::table);
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
      return triangular(peak, table_.y().front(), table_.x()[1], table_.x()[2]);
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
      return table_.clamped(t);
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
  return table_.integral(t) - table_.integral(0.0);
}

}  // namespace suite
