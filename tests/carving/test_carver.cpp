// Hierarchical carving: exact agreement with the plain voxel loop and with the original program on
// the real wheat grain, sub-voxel sampling, and the analytic visual hulls of spheres and ellipsoids.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::carving {
namespace {

const std::filesystem::path kWheat = SUITE_DATA_DIR "/kstate_wheat_36view/carve_input.dat";

// The silhouette of the ellipsoid x^T A x <= 1 seen by a parallel view: a pixel is seed when the
// ray through its centre meets the ellipsoid, i.e. when the minimum of the quadric along the ray
// is <= 1 (closed form for a line: p^T (A - A d d^T A / d^T A d) p with p any point of the ray).
Mask ellipsoid_mask(const Eigen::Matrix3d& A, const View& view) {
  const Eigen::Matrix3d M = view.P.leftCols<3>();
  const Eigen::Vector3d d = M.row(0).cross(M.row(1)).transpose();  // the viewing direction (null space of rows 0, 1)
  const Eigen::Matrix3d Q = A - (A * d) * (d.transpose() * A) / (d.transpose() * A * d);
  std::vector<std::uint8_t> px(static_cast<std::size_t>(view.width) * view.height);
  const Eigen::Matrix2d M2 = M.topRows<2>() * M.topRows<2>().transpose();
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      // A world point on the ray of pixel (x, y): least-norm solution of M[0:2] X = (x, y) - t.
      const Eigen::Vector2d rhs(x - view.P(0, 3), y - view.P(1, 3));
      const Eigen::Vector3d X = M.topRows<2>().transpose() * M2.ldlt().solve(rhs);
      px[static_cast<std::size_t>(y) * view.width + x] = X.dot(Q * X) <= 1.0 ? 1 : 0;
    }
  return Mask(view.width, view.height, std::move(px));
}

// A disc of radius R px centred at (cx, cy): the silhouette of a sphere centred on the axis.
Mask disc_mask(int width, int height, double cx, double cy, double R) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      px[static_cast<std::size_t>(y) * width + x] = (x - cx) * (x - cx) + (y - cy) * (y - cy) <= R * R ? 1 : 0;
  return Mask(width, height, std::move(px));
}

TEST(Carver, RealWheatGrainGivesTheOriginalProgramsVoxelCount) {
  // README of the reference data: the original program keeps exactly 25,234 voxels at 100^3.
  const CarveInput in = read_carve_input(kWheat);
  ASSERT_EQ(in.views.size(), 36u);
  EXPECT_EQ(carve_plain(in.views, in.masks, in.grid), 25234);
  const CarveResult r = carve(in.views, in.masks, in.grid);
  EXPECT_EQ(r.voxels, 25234);
  EXPECT_NEAR(r.volume_mm3, 25.234, 1e-9);
  // The hierarchy looks at far fewer cells than the grid has voxels.
  EXPECT_LT(r.stats.cells, in.grid.count() / 20);
}

TEST(Carver, HierarchyMatchesThePlainLoopVoxelForVoxel) {
  const CarveInput in = read_carve_input(kWheat);
  for (int n : {37, 64, 101, 150}) {  // odd sizes exercise clipped cells
    const VoxelGrid g = VoxelGrid::cube({0.1, -0.2, 0.05}, 8.0, n);
    EXPECT_EQ(carve(in.views, in.masks, g).voxels, carve_plain(in.views, in.masks, g)) << n;
    // Testing cells by their full extent (the sub-voxel mode) keeps the same centres.
    EXPECT_EQ(carve(in.views, in.masks, g, {2, false}).voxels, carve_plain(in.views, in.masks, g)) << n;
  }
}

TEST(Carver, SubvoxelSamplesEqualTheCentresOfTheRefinedGrid) {
  // s x s x s samples at sample centres of an n^3 grid are exactly the voxel centres of the
  // (s n)^3 grid, so both volumes agree to round-off.
  const CarveInput in = read_carve_input(kWheat);
  for (int s : {2, 3}) {
    const CarveResult coarse = carve(in.views, in.masks, VoxelGrid::cube({0, 0, 0}, 10.0, 64), {s, false});
    const CarveResult fine = carve(in.views, in.masks, VoxelGrid::cube({0, 0, 0}, 10.0, 64 * s));
    EXPECT_NEAR(coarse.subvoxel_volume_mm3, fine.volume_mm3, 1e-9 * fine.volume_mm3) << s;
  }
}

TEST(Carver, RealWheatGrainConvergesOnFinerGrids) {
  // README of the reference data: finer grids over the same masks converge to about 25.40 mm^3
  // (256^3: 25.4075); the issue asks for 0.1% of 25.40.
  constexpr double kConverged = 25.40, kTolerance = 1e-3;
  const CarveInput in = read_carve_input(kWheat);
  const CarveResult r256 = carve(in.views, in.masks, VoxelGrid::cube({0, 0, 0}, 10.0, 256));
  EXPECT_NEAR(r256.volume_mm3, kConverged, kTolerance * kConverged);
  const CarveResult sub = carve(in.views, in.masks, in.grid, {4, false});  // 100^3 with 4^3 samples at the boundary
  EXPECT_NEAR(sub.subvoxel_volume_mm3, kConverged, kTolerance * kConverged);
  // The bounding box of kept voxels is the grain's (about 6.0 x 2.7 x 3.4 mm at 0.1 mm voxels).
  EXPECT_EQ(r256.last[0] - r256.first[0] + 1, 156);
}

// Visual hull of a sphere of radius r from N equally spaced parallel views about one axis: a
// stack of regular N-gons (N even; 2N for odd N) circumscribing the sphere's circles, volume
// (4N/3) tan(pi/N) r^3 (docs/methods/carving.md).
double analytic_sphere_hull(int views, double r) {
  const int sides = views % 2 == 0 ? views : 2 * views;
  return 4.0 * sides / 3.0 * std::tan(std::numbers::pi / sides) * r * r * r;
}

TEST(Carver, SphereUnderParallelProjectionMatchesTheAnalyticHull) {
  // 0.1% (issue 4). Sources of error at 200 px per radius and 240^3 voxels with 2^3 sub-samples:
  // the pixelised disc (area error ~1e-5 of pi R^2) and the voxelised hull (unbiased boundary
  // error of a few 1e-4 on ~10^5 boundary voxels).
  constexpr double kTolerance = 1e-3;
  const double r = 2.0, scale = 100.0;
  for (int n_views : {4, 5, 8, 36}) {
    ParallelTurntable rig{scale, 250, 250, n_views, 0.0, 2 * std::numbers::pi / n_views, 500, 500};
    const auto views = rig.all_views();
    std::vector<Mask> masks(views.size(), disc_mask(500, 500, 250, 250, scale * r));
    const CarveResult hull = carve(views, masks, VoxelGrid::cube({0, 0, 0}, 2.1 * r, 240), {2, false});
    const double expected = analytic_sphere_hull(n_views, r);
    EXPECT_NEAR(hull.subvoxel_volume_mm3 / expected - 1, 0, kTolerance) << n_views << " views";
  }
}

TEST(Carver, SphereUnderCentralProjectionWithin0p3PercentOfItsVolume) {
  // Issue 4: 36 views, central projection, within 0.3% of the true volume. The hull's own bias
  // is +0.09 to +0.12% at 10-50 radii (docs/methods/carving.md); here the camera is at 25 radii.
  constexpr double kTolerance = 3e-3;
  const double r = 2.0, d = 50.0, f = 5000.0;
  Turntable rig{{f, 300, 300}, d, 36, 0.0, 2 * std::numbers::pi / 36, 600, 600};
  const auto views = rig.all_views();
  const double R = f * std::tan(std::asin(r / d));  // the image of the tangent cone
  std::vector<Mask> masks(views.size(), disc_mask(600, 600, 300, 300, R));
  const CarveResult hull = carve(views, masks, VoxelGrid::cube({0, 0, 0}, 2.1 * r, 240), {2, false});
  const double truth = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_GT(hull.subvoxel_volume_mm3, truth);  // a visual hull never loses volume
  EXPECT_NEAR(hull.subvoxel_volume_mm3 / truth - 1, 0, kTolerance);
}

TEST(Carver, SeedSizedEllipsoidsWithin0p5Percent) {
  // Issue 4: ellipsoids of seed size within 0.5% of their volume from 36 views. Wheat
  // (7.2 x 3.6 x 2.9 mm) and milo (3.9 x 3.8 x 2.5 mm) lying on the turntable: long axis
  // horizontal, tilted 20 degrees about it so no view is special.
  constexpr double kTolerance = 5e-3;
  const double scale = 60.0;  // px/mm: 216 px across the wheat grain's length
  for (const Eigen::Vector3d& axes : {Eigen::Vector3d(3.6, 1.45, 1.8), Eigen::Vector3d(1.95, 1.25, 1.9)}) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Matrix3d A = R * axes.cwiseInverse().cwiseAbs2().asDiagonal() * R.transpose();
    ParallelTurntable rig{scale, 280, 200, 36, 0.0, 2 * std::numbers::pi / 36, 560, 400};
    const auto views = rig.all_views();
    std::vector<Mask> masks;
    for (const auto& v : views) masks.push_back(ellipsoid_mask(A, v));
    const double side = 2.1 * axes.maxCoeff();
    const CarveResult hull = carve(views, masks, VoxelGrid::cube({0, 0, 0}, side, 256), {2, false});
    const double truth = 4.0 / 3.0 * std::numbers::pi * axes.prod();
    EXPECT_GT(hull.subvoxel_volume_mm3, truth * (1 - 1e-4)) << axes.transpose();
    EXPECT_NEAR(hull.subvoxel_volume_mm3 / truth - 1, 0, kTolerance) << axes.transpose();
  }
}

TEST(Carver, BadInputIsNamed) {
  const CarveInput in = read_carve_input(kWheat);
  std::vector<Mask> fewer(in.masks.begin(), in.masks.end() - 1);
  EXPECT_NE(testing::input_error_of([&] { carve(in.views, fewer, in.grid); }).find("36 views but 35 masks"),
            std::string::npos);
  auto wrong = in.views;
  wrong[3].width = 640;
  EXPECT_NE(testing::input_error_of([&] {
              carve(wrong, in.masks, in.grid);
            }).find("view 3: the mask is 200 x 200 px but the camera's image is 640 x 200 px"),
            std::string::npos);
  // A box so big it reaches behind the cameras (93 mm from the axis).
  EXPECT_NE(testing::input_error_of([&] {
              carve(in.views, in.masks, VoxelGrid::cube({0, 0, 0}, 400, 10));
            }).find("behind camera"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] {
              read_carve_input("/nonexistent/carve_input.dat");
            }).find("cannot read carving input '/nonexistent/carve_input.dat'"),
            std::string::npos);
}

TEST(CarveInputReader, TruncatedFileIsNamed) {
  const auto dir = std::filesystem::temp_directory_path() / "suite-carve-input-test";
  std::filesystem::create_directories(dir);
  const auto cut = dir / "cut.dat";
  {
    std::ifstream in(kWheat, std::ios::binary);
    std::vector<char> bytes(1000100);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const std::string message = testing::input_error_of([&] { read_carve_input(cut); });
  EXPECT_NE(message.find("ends inside view 0's projection matrix"), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace suite::carving
