// What the slice count buys in the two-view elliptic-slice model (issue 30, item 5): the volume
// error against the number of slices N, with and without the dissertation's neighbour averaging
// (slicing.neighbour_average), on exact silhouettes of shapes of known volume seen by a parallel
// top camera and a parallel side camera (the rig of carving/examples/synthetic/wheat_two_view.yaml):
//   wheat ellipsoid 7.2 x 3.6 x 2.9 mm; balls of 3.18 and 6.35 mm (the dissertation's check);
//   the milo superellipsoid (3.9 x 2.5 x 3.8 mm, exponents 0.8: not elliptic across); the creased
//   grain (the wheat ellipsoid with a 0.35 mm groove 0.5 mm deep, which neither view sees);
//   the real Kansas State grain: its 36-view visual hull (carve_input.dat carved at 320^3) seen
//   from above and from the side along its principal axes, the reference being that hull's own
//   voxel volume (so the error is the elliptic-slice model's and the pixels', not the hull's).
// Each shape is imaged at P sub-pixel positions (the seed's centre moved by fractions of a pixel);
// the CSV gives the mean, spread and worst error over them, at 20 and 40 px/mm.
//
//   two_view_slices [--out FILE.csv] [--positions P] [--repeats R] [--carve-input carve_input.dat]
//
// The time of measure_two_view (the masks already segmented) is the median of R repeats, each of
// many calls, on the first position's masks.
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "benchmarks/carving/bench_support.hpp"
#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "carving/slicing/two_view.hpp"

namespace {

using namespace suite::carving;
namespace b = suite::carving::bench;

constexpr int kWidth = 640, kHeight = 480;

// Top camera looking down (+y): u = s x + W/2, v = -s z + H/2; side camera along +z:
// u = s x + W/2 - 20, v = s y + H/2 + 10 (as tests/carving/test_two_view.cpp).
View top_view(double s) {
  View v;
  v.P << s, 0, 0, kWidth / 2.0, 0, 0, -s, kHeight / 2.0, 0, 0, 0, 1;
  v.width = kWidth, v.height = kHeight;
  return v;
}
View side_view(double s) {
  View v;
  v.P << s, 0, 0, kWidth / 2.0 - 20, 0, s, 0, kHeight / 2.0 + 10, 0, 0, 0, 1;
  v.width = kWidth, v.height = kHeight;
  return v;
}

// Position k of P: the centre moved by sub-pixel fractions (a low-discrepancy set), in mm.
Eigen::Vector3d offset_px(int k, int positions) {
  const auto frac = [](double x) { return x - std::floor(x); };
  return {(k + 0.5) / positions, frac(0.6180339887 * k + 0.13), frac(0.7548776662 * k + 0.41)};
}

// Lying flat: long axis along world x, width along world z (the top view's y), thickness along
// world y (vertical, the side view's y).
Pose lying_flat(const Eigen::Vector3d& centre) {
  Pose pose;
  pose.rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  pose.centre = centre;
  return pose;
}

struct Pair {
  Mask top, side;
};

struct Case {
  std::string shape;
  double px_per_mm = 0, true_mm3 = 0;
  std::vector<Pair> pairs;  // one per position
};

Case analytic_case(const std::string& name, double px_per_mm, int positions) {
  Case c{name, px_per_mm, 0, {}};
  for (int k = 0; k < positions; ++k) {
    const Pose pose = lying_flat(offset_px(k, positions) / px_per_mm);
    std::unique_ptr<Shape> shape;
    if (name == "wheat_ellipsoid") shape = std::make_unique<Ellipsoid>(3.6, 1.8, 1.45, pose);
    if (name == "ball_3.18mm") shape = std::make_unique<Sphere>(3.18 / 2, pose);
    if (name == "ball_6.35mm") shape = std::make_unique<Sphere>(6.35 / 2, pose);
    if (name == "milo_superellipsoid") shape = std::make_unique<Superellipsoid>(1.95, 1.25, 1.9, 0.8, 0.8, pose);
    if (name == "creased_grain") shape = std::make_unique<CreasedGrain>(3.6, 1.8, 1.45, 0.35, 0.5, pose);
    c.true_mm3 = shape->volume();
    c.pairs.push_back({render(*shape, top_view(px_per_mm)).mask, render(*shape, side_view(px_per_mm)).mask});
  }
  return c;
}

// The real grain: its visual hull from the 36 masks of carve_input.dat, carved at `cells`^3 over
// the file's box, then seen along its own principal axes (long axis = image x in both views, the
// middle axis across the top view, the shortest across the side view). A pixel is seed when the
// line through its centre along the viewing axis meets a kept voxel (marched at a third of a voxel).
struct Hull {
  VoxelGrid grid;
  std::vector<std::uint8_t> kept;
  double volume_mm3 = 0;
  Eigen::Vector3d mean{0, 0, 0};
  Eigen::Matrix3d axes;            // columns: long, middle, short
  Eigen::Vector3d reach{0, 0, 0};  // largest |offset| of a kept voxel's centre from `mean` along each axis, mm
  bool inside(const Eigen::Vector3d& X) const {
    const Eigen::Vector3d g = (X - grid.lo).cwiseQuotient(grid.voxel);
    const int i = static_cast<int>(std::floor(g.x())), j = static_cast<int>(std::floor(g.y())),
              k = static_cast<int>(std::floor(g.z()));
    if (i < 0 || j < 0 || k < 0 || i >= grid.n[0] || j >= grid.n[1] || k >= grid.n[2]) return false;
    return kept[(static_cast<std::size_t>(k) * grid.n[1] + j) * grid.n[0] + i] != 0;
  }
};

Hull real_grain_hull(const std::string& file, int cells) {
  const CarveInput in = read_carve_input(file);
  Hull h;
  h.grid.lo = -in.box_mm / 2;
  h.grid.voxel = in.box_mm / cells;
  h.grid.n = {cells, cells, cells};
  CarveOptions o;
  o.keep_cells = true;
  const CarveResult r = carve(in.views, in.masks, h.grid, o);
  h.kept.assign(static_cast<std::size_t>(h.grid.count()), 0);
  Eigen::Vector3d sum{0, 0, 0};
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  long long n = 0;
  for_each_kept_voxel(r, [&](int i, int j, int k) {
    h.kept[(static_cast<std::size_t>(k) * cells + j) * cells + i] = 1;
    const Eigen::Vector3d X = h.grid.centre(i, j, k);
    sum += X, second += X * X.transpose(), ++n;
  });
  h.volume_mm3 = r.volume_mm3;
  h.mean = sum / static_cast<double>(n);
  const Eigen::Matrix3d cov = second / static_cast<double>(n) - h.mean * h.mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending eigenvalues
  h.axes.col(0) = eig.eigenvectors().col(2);
  h.axes.col(1) = eig.eigenvectors().col(1);
  h.axes.col(2) = eig.eigenvectors().col(0);
  for_each_kept_voxel(r, [&](int i, int j, int k) {
    h.reach = h.reach.cwiseMax((h.axes.transpose() * (h.grid.centre(i, j, k) - h.mean)).cwiseAbs());
  });
  h.reach += Eigen::Vector3d::Constant(h.grid.voxel.maxCoeff());  // a voxel beyond its centre
  return h;
}

// The hull seen along axis `look` (2: from above, the top view; 1: from the side), the image's x
// along the long axis and its y along the remaining axis, at px_per_mm, the grid shifted by
// `shift` px.
Mask hull_view(const Hull& h, int look, double px_per_mm, const Eigen::Vector3d& shift) {
  const int across = look == 2 ? 1 : 2;
  const Eigen::Vector3d ex = h.axes.col(0), ey = h.axes.col(across), ez = h.axes.col(look);
  const double step = h.grid.voxel.minCoeff() / 3;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(kWidth) * kHeight, 0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double u = (x - kWidth / 2.0 - shift.x()) / px_per_mm, v = (y - kHeight / 2.0 - shift.y()) / px_per_mm;
      if (std::abs(u) > h.reach(0) || std::abs(v) > h.reach(across)) continue;
      const Eigen::Vector3d base = h.mean + u * ex + v * ey;
      for (double t = -h.reach(look); t <= h.reach(look); t += step)
        if (h.inside(base + t * ez)) {
          pixels[static_cast<std::size_t>(y) * kWidth + x] = 1;
          break;
        }
    }
  return Mask(kWidth, kHeight, std::move(pixels));
}

Case real_grain_case(const Hull& h, double px_per_mm, int positions) {
  Case c{"kstate_wheat_hull", px_per_mm, h.volume_mm3, {}};
  for (int k = 0; k < positions; ++k) {
    const Eigen::Vector3d s = offset_px(k, positions);
    c.pairs.push_back({hull_view(h, 2, px_per_mm, s), hull_view(h, 1, px_per_mm, {s.x(), s.z(), 0})});
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = b::flag_value(argc, argv, "--out", "two_view_slices.csv");
  const int positions = std::stoi(b::flag_value(argc, argv, "--positions", "8"));
  const int repeats = std::stoi(b::flag_value(argc, argv, "--repeats", "5"));
  const std::string carve_input = b::flag_value(argc, argv, "--carve-input", SUITE_CARVING_REFERENCE_INPUT);
  const std::vector<int> slice_counts{3, 5, 8, 10, 15, 20, 30, 50, 75, 100, 200, 400};

  std::ofstream csv(out);
  csv << b::csv_header("two_view_slices",
                       fmt::format("exact silhouettes, parallel top and side views, {} sub-pixel positions per shape; "
                                   "error = volume / true - 1; slicing_us = median of {} repeats",
                                   positions, repeats))
      << "shape,px_per_mm,slices,neighbour_average,true_mm3,mean_error_pct,sd_error_pct,min_error_pct,max_error_pct,"
         "max_abs_error_pct,slicing_us\n";

  std::printf("carving the real grain's hull (320^3) ...\n");
  const Hull hull = real_grain_hull(carve_input, 320);
  std::printf("hull %.4f mm^3, axes along the world: long (%.2f %.2f %.2f)\n", hull.volume_mm3, hull.axes(0, 0),
              hull.axes(1, 0), hull.axes(2, 0));

  for (const double px_per_mm : {40.0, 20.0}) {
    std::vector<Case> cases;
    for (const char* name : {"wheat_ellipsoid", "ball_3.18mm", "ball_6.35mm", "milo_superellipsoid", "creased_grain"})
      cases.push_back(analytic_case(name, px_per_mm, positions));
    cases.push_back(real_grain_case(hull, px_per_mm, positions));
    for (const Case& c : cases)
      for (const bool average : {false, true})
        for (const int n : slice_counts) {
          SlicingOptions o;
          o.slices = n;
          o.px_per_mm_top = px_per_mm;
          o.neighbour_average = average;
          std::vector<double> e;
          for (const Pair& p : c.pairs)
            e.push_back(100 * (measure_two_view(p.top, p.side, o).volume_mm3 / c.true_mm3 - 1));
          double mean = 0, sq = 0, lo = e[0], hi = e[0], worst = 0;
          for (double x : e)
            mean += x, lo = std::min(lo, x), hi = std::max(hi, x), worst = std::max(worst, std::abs(x));
          mean /= static_cast<double>(e.size());
          for (double x : e) sq += (x - mean) * (x - mean);
          const double sd = e.size() > 1 ? std::sqrt(sq / static_cast<double>(e.size() - 1)) : 0;
          constexpr int kCalls = 200;
          double sink = 0;
          const double t =
              b::median(b::time_repeats(repeats,
                                        [&] {
                                          for (int i = 0; i < kCalls; ++i)
                                            sink += measure_two_view(c.pairs[0].top, c.pairs[0].side, o).volume_mm3;
                                        })) /
              kCalls;
          if (sink < 0) return 1;
          csv << fmt::format("{},{},{},{},{:.6f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.2f}\n", c.shape, px_per_mm, n,
                             average ? 1 : 0, c.true_mm3, mean, sd, lo, hi, worst, 1e6 * t);
          std::printf("%-20s %3.0f px/mm N = %3d %s: mean %+.3f%%, sd %.3f%%, worst |e| %.3f%%, %.1f us\n",
                      c.shape.c_str(), px_per_mm, n, average ? "averaged" : "plain   ", mean, sd, worst, 1e6 * t);
        }
  }
  return 0;
}
