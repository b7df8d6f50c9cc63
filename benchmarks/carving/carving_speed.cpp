// Speed of seed carving on one core (issue 4's benchmark list, items 1 and 2):
//   1. time per seed of the hierarchical carve, 36 views, at 100^3 .. 625^3 voxels over a
//      cube holding the seed: the real K-State grain (carve_input.dat, its 10 mm cube) and a
//      rendered wheat-sized ellipsoid (8 mm cube); the plain voxel loop with early exit
//      (carve_plain) as the baseline, timed alternately with the hierarchy so their ratio holds on
//      a noisy machine; and the full measure_hull (search, fine carve at 256, mesh at 128);
//   2. two-view slicing: images per second, segmentation of the colour images included.
//
//   carving_speed [--out FILE.csv] [--repeats R] [--carve-input FILE] [--plain-limit S]
//
// Times are medians of R repeats (default 7). The plain loop runs up to 512^3 while its expected
// time stays under S seconds (default 10). OpenCV is held to one thread.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "benchmarks/carving/bench_support.hpp"
#include "benchmarks/carving/synthetic_seeds.hpp"
#include "benchmarks/carving/two_view_speed.hpp"
#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "carving/measure/hull_measurement.hpp"

namespace {

using namespace suite::carving;
using suite::carving::bench::median;
using suite::carving::bench::time_repeats;

struct Row {
  std::string benchmark, input, method;
  int resolution = 0, views = 0, repeats = 0;
  std::vector<double> seconds{};
  long long voxels = 0;
  double volume_mm3 = 0;
  CarveStats stats{};
  std::string note{};
};

// One seed's views and masks with the cube its effective resolution refers to.
struct CarveCase {
  std::string name;
  std::vector<View> views;
  std::vector<Mask> masks;
  Eigen::Vector3d centre{0, 0, 0};
  double side_mm = 0;
};

// Hierarchical and plain carves, timed alternately (one of each per repeat). 100^3 is the original
// program's grid; 625^3 the dissertation's finest (hierarchical only). The plain loop runs up to
// 512^3 while its time, extrapolated as n^3 from the previous resolution, stays under the limit.
void time_carves(const CarveCase& c, int repeats, double plain_limit_s, std::vector<Row>& rows) {
  double plain_s = 0;
  int plain_n = 0;
  for (int n : {100, 128, 256, 512, 625}) {
    const VoxelGrid grid = VoxelGrid::cube(c.centre, c.side_mm, n);
    const int views = static_cast<int>(c.views.size());
    Row h{"carve", c.name, "hierarchical", n, views, repeats};
    Row p{"carve", c.name, "plain", n, views, repeats};
    const double estimate = plain_n ? plain_s * std::pow(static_cast<double>(n) / plain_n, 3) : 0;
    const bool plain = n <= 512 && estimate < plain_limit_s;
    for (int r = 0; r < repeats; ++r) {
      CarveResult result;
      h.seconds.push_back(time_repeats(1, [&] { result = carve(c.views, c.masks, grid); })[0]);
      h.voxels = result.voxels, h.volume_mm3 = result.volume_mm3, h.stats = result.stats;
      if (plain) p.seconds.push_back(time_repeats(1, [&] { p.voxels = carve_plain(c.views, c.masks, grid); })[0]);
    }
    rows.push_back(h);
    if (plain) {
      p.volume_mm3 = static_cast<double>(p.voxels) * grid.voxel_volume();
      if (p.voxels != h.voxels)
        p.note = fmt::format("voxel counts differ: plain {} hierarchical {}", p.voxels, h.voxels);
      plain_s = median(p.seconds), plain_n = n;
      rows.push_back(p);
    } else if (n <= 512) {
      p.repeats = 0;
      p.note = fmt::format("skipped: about {:.1f} s expected > {} s", estimate, plain_limit_s);
      rows.push_back(p);
    }
  }
}

// The whole measurement: coarse search, fine carve at 256 along the seed's longest side, mesh at 128.
void time_measure_hull(const CarveCase& c, int repeats, int subvoxel, std::vector<Row>& rows) {
  HullOptions o;  // resolution 256, search 48, mesh at 128
  o.subvoxel_samples = subvoxel;
  Row row{"measure_hull",
          c.name,
          fmt::format("search+carve+mesh s={}", subvoxel),
          o.resolution,
          static_cast<int>(c.views.size()),
          repeats};
  HullMeasurement m;
  row.seconds = time_repeats(repeats, [&] { m = measure_hull(c.views, c.masks, o); });
  row.voxels = m.voxels, row.volume_mm3 = m.volume_mm3, row.stats = m.stats;
  row.note = fmt::format("{:.3f} x {:.3f} x {:.3f} mm, surface {:.2f} mm^2, {} triangles", m.length_mm, m.width_mm,
                         m.thickness_mm, m.surface_mm2, m.mesh.triangles.size());
  rows.push_back(row);
}

void write_csv(const std::string& path, const std::string& header, const std::vector<Row>& rows) {
  std::ofstream csv(path);
  csv << header;
  csv << "benchmark,input,method,resolution,views,repeats,median_s,min_s,max_s,voxels,volume_mm3,cells,view_tests,"
         "point_tests,note\n";
  for (const Row& r : rows) {
    const auto [lo, hi] = r.seconds.empty() ? std::pair{0.0, 0.0}
                                            : std::pair{*std::min_element(r.seconds.begin(), r.seconds.end()),
                                                        *std::max_element(r.seconds.begin(), r.seconds.end())};
    csv << fmt::format("{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{},{:.6f},{},{},{},\"{}\"\n", r.benchmark, r.input,
                       r.method, r.resolution, r.views, r.repeats, r.seconds.empty() ? 0.0 : median(r.seconds), lo, hi,
                       r.voxels, r.volume_mm3, r.stats.cells, r.stats.view_tests, r.stats.point_tests, r.note);
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace b = suite::carving::bench;
  const std::string out_csv = b::flag_value(argc, argv, "--out", "");
  const int repeats = std::stoi(b::flag_value(argc, argv, "--repeats", "7"));
  const double plain_limit_s = std::stod(b::flag_value(argc, argv, "--plain-limit", "10"));
  const std::string input = b::flag_value(argc, argv, "--carve-input", SUITE_CARVING_REFERENCE_INPUT);
  cv::setNumThreads(1);  // one core: segmentation must not spread over OpenCV's thread pool

  const CarveInput real = read_carve_input(input);
  const b::SyntheticSeed wheat = b::wheat_ellipsoid(36);
  const std::vector<CarveCase> cases = {{"real_grain", real.views, real.masks, {0, 0, 0}, real.box_mm.maxCoeff()},
                                        {"wheat_ellipsoid", wheat.views, wheat.masks, {0, 0, 0}, wheat.cube_side_mm}};
  std::vector<Row> rows;
  for (const CarveCase& c : cases) {
    time_carves(c, repeats, plain_limit_s, rows);
    time_measure_hull(c, repeats, 0, rows);
    time_measure_hull(c, repeats, 2, rows);
  }
  const b::TwoViewTiming tv = b::time_two_view(repeats, 20);
  const std::string tv_note = fmt::format("volume {:.4f} mm^3 vs true {:.4f} mm^3; {} batches of {}", tv.volume_mm3,
                                          tv.true_mm3, tv.batches, tv.per_batch);
  for (const auto& [method, s] : {std::pair{"segment x2 + slice (one pair)", tv.pair_s},
                                  std::pair{"segment (one image)", tv.segment_s}, std::pair{"slice", tv.slicing_s}}) {
    Row r{"two_view", "wheat_two_view", method, 50, 2, repeats, {s}};
    r.volume_mm3 = tv.volume_mm3, r.note = tv_note;
    rows.push_back(r);
  }

  std::printf("%-13s %-16s %-30s %5s %11s %11s %s\n", "benchmark", "input", "method", "res", "median s", "voxels",
              "note");
  for (const Row& r : rows)
    std::printf("%-13s %-16s %-30s %5d %11.5f %11lld %s\n", r.benchmark.c_str(), r.input.c_str(), r.method.c_str(),
                r.resolution, r.seconds.empty() ? 0.0 : median(r.seconds), r.voxels, r.note.c_str());
  std::printf("two-view slicing: %.1f images per second per core (%.2f ms per pair)\n", 2 / tv.pair_s, tv.pair_s * 1e3);
  if (!out_csv.empty())
    write_csv(out_csv, b::csv_header("carving_speed", fmt::format("one core, medians of {} repeats", repeats)), rows);
  return 0;
}
