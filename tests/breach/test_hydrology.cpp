// Inflow hydrographs and stage-storage relations: values, exact volumes, inverses, and the
// messages for bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "core/config/config.hpp"
#include "core/tables/hydrograph.hpp"
#include "solvers/breach/hydrology/stage_storage.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::Hydrograph;
using suite::breach::StageStorage;
using suite::config::Config;
using suite::testing::input_error_of;

constexpr double kCfs = 0.028316846592;  // m^3/s (exact: 0.3048^3)

// Trapezoid-rule integral of h over [a, b] with n panels: error <= (b-a) h^2 max|Q''| / 12.
double trapezoid(const Hydrograph& q, double a, double b, int n) {
  const double dt = (b - a) / n;
  double s = 0.5 * (q(a) + q(b));
  for (int i = 1; i < n; ++i) s += q(a + i * dt);
  return s * dt;
}

TEST(Hydrograph, WinDamStyleTableInHoursAndCfs) {
  auto cfg = Config::from_string("inflow:\n  type: table\n  table: [[0 h, 0 cfs], [2 h, 1200 cfs], [6 h, 0 cfs]]\n",
                                 "dam.yaml");
  const auto q = Hydrograph::read(cfg.root().section("inflow"));
  EXPECT_NEAR(q(3600.0), 600 * kCfs, 1e-12);
  EXPECT_NEAR(q(2 * 3600.0), 1200 * kCfs, 1e-12);
  EXPECT_EQ(q(-5.0), 0.0);
  EXPECT_EQ(q(1e6), 0.0);
  // Triangle area: 0.5 x 6 h x 1200 cfs, exact (piecewise linear).
  EXPECT_NEAR(q.volume(0.0, 6 * 3600.0), 0.5 * 6 * 3600.0 * 1200 * kCfs, 1e-9);
  EXPECT_NEAR(q.volume(1800.0, 9000.0), trapezoid(q, 1800.0, 9000.0, 5400), 1e-6);
  EXPECT_EQ(q.breakpoints().size(), 3u);
}

TEST(Hydrograph, AnalyticFormsIntegrateInClosedForm) {
  // Sine of the dissertation's inlet law: its mean over whole periods is half the peak.
  const auto s = Hydrograph::sine(2.0, 10.0);
  EXPECT_NEAR(s(2.5), 2.0, 1e-15);  // quarter period: sin = 1
  EXPECT_NEAR(s.volume(0.0, 30.0), 30.0, 1e-12);
  // Over a part period, the closed form against a fine trapezoid rule:
  // error <= 7.3 x (7.3/20000)^2 x (peak (2 pi/T)^2 / 2) / 12 ~ 3e-6.
  EXPECT_NEAR(s.volume(1.1, 8.4), trapezoid(s, 1.1, 8.4, 20000), 3e-6);
  const auto t = Hydrograph::triangular(100.0, 10.0, 3600.0, 4 * 3600.0);
  EXPECT_DOUBLE_EQ(t(1800.0), 55.0);
  EXPECT_DOUBLE_EQ(t(5 * 3600.0), 10.0);
  EXPECT_NEAR(t.volume(0.0, 4 * 3600.0), (10.0 + 0.5 * 90.0) * 4 * 3600.0, 1e-8);
  EXPECT_DOUBLE_EQ(Hydrograph::constant(3.0).volume(2.0, 5.0), 9.0);
}

TEST(Hydrograph, BadInputIsRejectedWithTheKey) {
  auto decreasing =
      Config::from_string("inflow:\n  type: table\n  table: [[0 h, 0 cfs], [2 h, 5 cfs], [1 h, 0 cfs]]\n", "d.yaml");
  const std::string msg = input_error_of([&] { Hydrograph::read(decreasing.root().section("inflow")); });
  EXPECT_NE(msg.find("d.yaml:3:10: key 'inflow.table'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("times must increase, but row 3 (3600 s) does not come after row 2 (7200 s)"), std::string::npos)
      << msg;
  auto unit = Config::from_string("inflow:\n  type: table\n  table: [[0 h, 0 furlongs]]\n", "u.yaml");
  EXPECT_NE(input_error_of([&] { Hydrograph::read(unit.root().section("inflow")); }).find("row 1, entry 2"),
            std::string::npos);
  auto kind = Config::from_string("inflow:\n  type: sinus\n", "k.yaml");
  EXPECT_NE(input_error_of([&] { Hydrograph::read(kind.root().section("inflow")); }).find("did you mean 'sine'?"),
            std::string::npos);
  auto tri =
      Config::from_string("inflow: {type: triangular, peak: 5 cfs, time_to_peak: 3 h, duration: 2 h}\n", "t.yaml");
  EXPECT_NE(input_error_of([&] {
              Hydrograph::read(tri.root().section("inflow"));
            }).find("must be longer than time_to_peak (10800 s)"),
            std::string::npos);
}

TEST(Hydrograph, TableFromAFileBesideTheScene) {
  // WinDAM users keep hydrographs as two-column files in hours and cfs; the path is relative to
  // the scene file's folder.
  const auto dir = std::filesystem::temp_directory_path() / ("suite-hydrograph-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "storm.csv") << "# design storm\ntime_h,discharge_cfs\n0,0\n2,1200\n6\t0\n";
  std::ofstream(dir / "dam.yaml") << "inflow:\n  type: table\n  file: storm.csv\n  columns: [h, cfs]\n";
  auto cfg = Config::from_file(dir / "dam.yaml");
  const auto q = Hydrograph::read(cfg.root().section("inflow"));
  EXPECT_NEAR(q(3600.0), 600 * kCfs, 1e-12);
  EXPECT_NEAR(q.volume(0.0, 6 * 3600.0), 0.5 * 6 * 3600.0 * 1200 * kCfs, 1e-9);
  std::ofstream(dir / "bad.csv") << "0,0\n2,1200\n3;lots\n";
  auto bad = Config::from_file(dir / "dam.yaml", {"inflow.file=bad.csv"});
  EXPECT_NE(input_error_of([&] {
              Hydrograph::read(bad.root().section("inflow"));
            }).find("bad.csv:3: expected two numbers (time in h, discharge in cfs), got '3 lots'"),
            std::string::npos);
  auto missing = Config::from_file(dir / "dam.yaml", {"inflow.file=nothere.csv"});
  EXPECT_NE(input_error_of([&] { Hydrograph::read(missing.root().section("inflow")); }).find("no such file"),
            std::string::npos);
  auto unit = Config::from_file(dir / "dam.yaml", {"inflow.columns=[h, feet]"});
  EXPECT_NE(input_error_of([&] { Hydrograph::read(unit.root().section("inflow")); }).find("key 'inflow.columns'"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(StageStorage, PowerLawAreaIsTheDerivativeAndLevelTheInverse) {
  const auto s = StageStorage::power_law(1.5e4, 2.0, 2.3);
  for (double h : {2.5, 4.0, 9.0}) {
    const double dh = 1e-4;  // central difference: error ~ dh^2 V''' / 6, far below 1e-6 relative
    EXPECT_NEAR(s.area(h), (s.volume(h + dh) - s.volume(h - dh)) / (2 * dh), 1e-6 * s.area(h));
    EXPECT_NEAR(s.level(s.volume(h)), h, 1e-12 * h);
  }
  EXPECT_EQ(s.volume(1.0), 0.0);
  EXPECT_EQ(s.level(0.0), 2.0);
}

TEST(StageStorage, TableInterpolatesExtrapolatesAndInverts) {
  auto cfg = Config::from_string(
      "storage:\n  type: table\n  table: [[100 ft, 0 m^3], [110 ft, 2e5 m^3], [120 ft, 9e5 m^3]]\n", "r.yaml");
  const auto s = StageStorage::read(cfg.root().section("storage"));
  const double h1 = 110 * 0.3048, h2 = 120 * 0.3048, dz = 10 * 0.3048;
  EXPECT_NEAR(s.area(h1 - 1.0), 2e5 / dz, 1e-6);
  EXPECT_NEAR(s.area(h1 + 1.0), 7e5 / dz, 1e-6);
  EXPECT_NEAR(s.volume(h2 + 1.0), 9e5 + 7e5 / dz, 1e-6) << "vertical walls above the last row";
  for (double v : {1e3, 2e5, 5.5e5, 1.2e6}) EXPECT_NEAR(s.volume(s.level(v)), v, 1e-9 * v);
  // A table starting above zero storage continues its first area down to a bottom at zero.
  const auto above = StageStorage::table({6.0, 8.0}, {1e6, 3e6});  // area 1e6 m^2 -> bottom at 5 m
  EXPECT_NEAR(above.bottom(), 5.0, 1e-12);
  EXPECT_NEAR(above.volume(5.5), 5e5, 1e-6);
  EXPECT_EQ(above.volume(4.0), 0.0);
  EXPECT_NEAR(above.level(2.5e5), 5.25, 1e-12);
  EXPECT_NEAR(above.level(0.0), 5.0, 1e-12);
  auto bad = Config::from_string("storage:\n  type: table\n  table: [[0 m, 0 m^3], [1 m, 0 m^3]]\n", "b.yaml");
  EXPECT_NE(input_error_of([&] {
              StageStorage::read(bad.root().section("storage"));
            }).find("volumes must increase, but row 2 (0 m^3) does not exceed row 1 (0 m^3)"),
            std::string::npos);
}

}  // namespace
