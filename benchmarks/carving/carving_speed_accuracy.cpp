// Speed versus accuracy of the hierarchical carve (issue 4's benchmark list, item 4), on exact
// rendered silhouettes so that only the method's error shows:
//   resolution sweep: 36 views, 32^3 .. 512^3 voxel centres over the seed's cube;
//   view sweep: N = 4 .. 72 views equally spaced over a full turn, 256^3;
// for a sphere under parallel projection (whose visual hull is analytic: (4N/3) tan(pi/N) r^3),
// a sphere under central projection, a wheat-sized ellipsoid and a creased grain (whose crease
// the silhouettes cannot see). A third table sets the crease's size against what the hull misses.
//
//   carving_speed_accuracy [--out FILE.csv] [--crease-out FILE.csv] [--repeats R]
//
// Times are medians of R repeats (default 5) on one core.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "benchmarks/carving/bench_support.hpp"
#include "benchmarks/carving/synthetic_seeds.hpp"
#include "carving/hull/carver.hpp"

namespace {

using namespace suite::carving;
namespace b = suite::carving::bench;

constexpr int kAllViews = 72;  // rendered once; N views are every (72/N)-th of them

struct Point {
  std::string sweep, shape, projection;
  int views = 0, resolution = 0;
  double median_s = 0, volume_mm3 = 0, true_mm3 = 0, hull_mm3 = 0;  // hull_mm3: analytic visual hull, 0 if none
  bool touches_border = false;
};

Point carve_point(const std::string& sweep, const b::SyntheticSeed& seed, int views, int resolution, int repeats) {
  const b::SyntheticSeed s = b::every_nth_view(seed, views);
  const VoxelGrid grid = s.cube(resolution);
  CarveResult r;
  const double t = b::median(b::time_repeats(repeats, [&] { r = carve(s.views, s.masks, grid); }));
  Point p{sweep, s.name, s.projection, views, resolution, t, r.volume_mm3, s.shape->volume()};
  if (s.projection == "parallel") p.hull_mm3 = b::analytic_sphere_hull_mm3(views, 2.0);
  for (int a = 0; a < 3; ++a) p.touches_border |= r.first[a] == 0 || r.last[a] == grid.n[a] - 1;
  return p;
}

// The crease table: how much of grooves of several sizes the 36-view hull misses, with one view
// looking exactly along the crease (turn 0) and with none (turn 5 deg, halfway between views).
void crease_table(const std::string& path, const std::string& header, int repeats) {
  std::ofstream csv(path);
  csv << header
      << "crease_radius_mm,crease_depth_mm,turn_deg,true_mm3,ellipsoid_mm3,groove_mm3,hull_mm3,error_pct,"
         "ellipsoid_hull_mm3,ellipsoid_bias_pct,groove_missed_pct,median_s\n";
  std::printf("\ncrease (36 views, 256^3): radius depth turn | true hull error%% | groove missed%%\n");
  for (double turn_deg : {0.0, 5.0}) {
    const double turn = turn_deg * std::numbers::pi / 180;
    const b::SyntheticSeed plain = b::uncreased_grain(36, turn);
    const CarveResult e = carve(plain.views, plain.masks, plain.cube(256));
    const double e_true = plain.shape->volume();
    for (const auto& [radius, depth] : {std::pair{0.35, 0.25}, std::pair{0.35, 0.5}, std::pair{0.35, 0.75},
                                        std::pair{0.2, 0.5}, std::pair{0.5, 0.5}}) {
      const b::SyntheticSeed g = b::creased_grain(36, radius, depth, turn);
      CarveResult r;
      const double t = b::median(b::time_repeats(repeats, [&] { r = carve(g.views, g.masks, g.cube(256)); }));
      const double truth = g.shape->volume(), groove = e_true - truth;
      // What the hull keeps beyond the truth, less the ellipsoid's own hull bias: the groove left in.
      const double missed = (r.volume_mm3 - truth) - (e.volume_mm3 - e_true);
      csv << fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.6f},{:.5f},{:.3f},{:.6g}\n", radius, depth,
                         turn_deg, truth, e_true, groove, r.volume_mm3, 100 * (r.volume_mm3 / truth - 1), e.volume_mm3,
                         100 * (e.volume_mm3 / e_true - 1), 100 * missed / groove, t);
      std::printf("  %.2f %.2f %3.0f | %8.4f %8.4f %+7.3f | %6.1f\n", radius, depth, turn_deg, truth, r.volume_mm3,
                  100 * (r.volume_mm3 / truth - 1), 100 * missed / groove);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_csv = b::flag_value(argc, argv, "--out", "");
  const std::string crease_csv = b::flag_value(argc, argv, "--crease-out", "");
  const int repeats = std::stoi(b::flag_value(argc, argv, "--repeats", "5"));
  const std::string header =
      b::csv_header("carving_speed_accuracy", fmt::format("one core, medians of {} repeats, exact masks", repeats));

  // The spheres at two pixel scales: 500 px per radius shows the visual hull's own bias, 200 px
  // adds the pixels' share (nearest-pixel rounding in every view). The creased grain is turned
  // 5 deg so that no view of 36 looks along its crease (the case the hull cannot see into).
  const double turn_5deg = 5 * std::numbers::pi / 180;
  const std::vector<b::SyntheticSeed> seeds = {
      b::parallel_sphere(kAllViews, 250),  b::parallel_sphere(kAllViews, 100),
      b::pinhole_sphere(kAllViews, 12500), b::pinhole_sphere(kAllViews, 5000),
      b::wheat_ellipsoid(kAllViews),       b::creased_grain(kAllViews, 0.35, 0.5, turn_5deg)};
  std::vector<Point> points;
  for (const auto& seed : seeds) {
    for (int n : {32, 48, 64, 96, 128, 192, 256, 384, 512})
      points.push_back(carve_point("resolution", seed, 36, n, repeats));
    for (int v : {4, 6, 8, 12, 18, 24, 36, 72}) points.push_back(carve_point("views", seed, v, 256, repeats));
  }

  std::printf("%-10s %-22s %5s %5s %10s %11s %11s %9s %9s\n", "sweep", "shape", "N", "res", "median s", "volume",
              "true", "error %", "hull %");
  for (const Point& p : points)
    std::printf("%-10s %-22s %5d %5d %10.5f %11.5f %11.5f %+9.4f %9s%s\n", p.sweep.c_str(), p.shape.c_str(), p.views,
                p.resolution, p.median_s, p.volume_mm3, p.true_mm3, 100 * (p.volume_mm3 / p.true_mm3 - 1),
                p.hull_mm3 > 0 ? fmt::format("{:+.4f}", 100 * (p.hull_mm3 / p.true_mm3 - 1)).c_str() : "",
                p.touches_border ? "  (touches the cube's border)" : "");
  if (!out_csv.empty()) {
    std::ofstream csv(out_csv);
    csv << header
        << "# error_pct = volume / true - 1; analytic_hull_pct = analytic visual hull / true - 1 (parallel sphere "
           "only); vs_analytic_pct = volume / analytic hull - 1\n"
        << "sweep,shape,projection,views,resolution,median_s,volume_mm3,true_mm3,error_pct,analytic_hull_mm3,"
           "analytic_hull_pct,vs_analytic_pct,touches_border\n";
    for (const Point& p : points)
      csv << fmt::format(
          "{},{},{},{},{},{:.6g},{:.6f},{:.6f},{:.5f},{:.6f},{},{},{}\n", p.sweep, p.shape, p.projection, p.views,
          p.resolution, p.median_s, p.volume_mm3, p.true_mm3, 100 * (p.volume_mm3 / p.true_mm3 - 1), p.hull_mm3,
          p.hull_mm3 > 0 ? fmt::format("{:.5f}", 100 * (p.hull_mm3 / p.true_mm3 - 1)) : "",
          p.hull_mm3 > 0 ? fmt::format("{:.5f}", 100 * (p.volume_mm3 / p.hull_mm3 - 1)) : "", p.touches_border ? 1 : 0);
  }
  if (!crease_csv.empty()) crease_table(crease_csv, header, repeats);
  return 0;
}
