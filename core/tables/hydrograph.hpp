#pragma once
// Inflow hydrographs Q_in(t): the breach model's reservoir inflow, foam-erosion's and mpm2grid's
// inlets. Time in s, discharge in m^3/s (mpm2grid: m^2/s per metre of width).
//
//   table:      linear interpolation between (time, discharge) points; before the first point
//               the first discharge, after the last the last (WinDAM users give hours and cfs)
//   constant:   Q(t) = peak
//   sine:       Q(t) = peak (0.5 + 0.5 sin(2 pi t / period)), the dissertation's inlet law
//               f = 0.5 + 0.5 sin(0.2 pi t) with period 10 s (Table 3.2, flow f1)
//   triangular: a storm rising linearly from `base` at t = 0 to `peak` at `time_to_peak`,
//               falling linearly back to `base` at `duration`, then `base`
// Scene form (section `inflow`):
//   type: table                          type: triangular
//   table: [[0 h, 0 cfs], [2 h, 1200 cfs]]   peak: 1200 cfs, base: 0 cfs, time_to_peak: 2 h, duration: 8 h
// or a table from a file of two columns (comma, semicolon, tab or space separated; '#' comments
// and one header line allowed), with the columns' units:
//   type: table
//   file: storm.csv          # relative to the scene file's folder
//   columns: [h, cfs]        # default [s, m^3/s]
#include <filesystem>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/tables/piecewise_linear.hpp"

namespace suite {

class Hydrograph {
 public:
  enum class Kind { table, constant, sine, triangular };

  static Hydrograph table(std::vector<double> times, std::vector<double> discharges);  // InputError if bad
  static Hydrograph constant(double discharge);
  static Hydrograph sine(double peak, double period);
  static Hydrograph triangular(double peak, double base, double time_to_peak, double duration);
  // Reads the `inflow` section described above; InputError names the key (or the file and line).
  static Hydrograph read(const config::Section& section);
  static Hydrograph read_file(const std::filesystem::path& path, const std::string& time_unit,
                              const std::string& discharge_unit);

  // The same storm with another peak (m^3/s): a triangle keeps its base and times, a sine its
  // period, a constant inflow becomes `peak`. InputError for a table.
  Hydrograph with_peak(double peak) const;
  // m^3/s: the discharge a triangle starts and ends at (0 for the other kinds).
  double base() const { return kind_ == Kind::triangular ? table_.y().front() : 0.0; }

  double operator()(double t) const;  // m^3/s
  // Exact volume between t0 and t1 (m^3): piecewise-linear and sine forms integrate in closed
  // form, so the reservoir mass balance can be checked to round-off.
  double volume(double t0, double t1) const;
  // The same as a running total from t = 0, in O(log n): volume(t0, t1) = cumulative(t1) -
  // cumulative(t0). The breach integrator evaluates it at every stage of every step.
  double cumulative(double t) const;
  // Times where the hydrograph has a kink (table points, triangle corners): an adaptive
  // integrator should step onto them rather than across.
  const std::vector<double>& breakpoints() const { return table_.x(); }
  Kind kind() const { return kind_; }

 private:
  Kind kind_ = Kind::constant;
  PiecewiseLinear table_;  // table and triangular (as a table)
  double peak_ = 0.0, period_ = 0.0;
};

}  // namespace suite
