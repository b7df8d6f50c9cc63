// measure_hull on rigs whose world frame does not put the seed at the origin (carving/measure/
// hull_measurement.hpp): the search cube is centred where the silhouettes' lines of sight meet, so
// a projection-matrix set calibrated in any frame measures the seed as the turntable frame does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "carving/measure/hull_measurement.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"

namespace suite::carving {
namespace {

TEST(HullMeasurement, ASeedAwayFromTheWorldOriginIsFoundAndMeasured) {
  // A wheat-sized ellipsoid on an 18-view pinhole turntable (60 px/mm on the axis).
  const Turntable rig{{6000, 320, 240}, 100, 18, 0.0, 2 * std::numbers::pi / 18, 640, 480};
  const Ellipsoid seed(3.6, 1.45, 1.8);
  std::vector<View> views = rig.all_views();
  std::vector<Mask> masks;
  for (const View& v : views) masks.push_back(render(seed, v).mask);
  HullOptions options;
  options.resolution = 128;
  options.mesh = false;
  const HullMeasurement at_origin = measure_hull(views, masks, options);
  // The same cameras and photographs, calibrated in a frame where the seed sits at `offset` (mm):
  // X' = X + offset, so P' = P [I, -offset; 0, 1].
  const Eigen::Vector3d offset(12, -7, 30);
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.topRightCorner<3, 1>() = -offset;
  std::vector<View> moved = views;
  for (View& v : moved) v.P = v.P * shift;
  EXPECT_LT((silhouette_centre(moved, masks) - offset).norm(), 0.05) << "mm: the seed's centre from its views";
  const HullMeasurement away = measure_hull(moved, masks, options);
  std::printf("hull volume %.4f mm^3 at the origin, %.4f mm^3 calibrated 33 mm away (true %.4f)\n",
              at_origin.volume_mm3, away.volume_mm3, seed.volume());
  // The two carve the same hull on lattices placed differently: they agree to the voxel
  // quantisation of a 128-voxel box (under 0.5% here), and both sit on the 18-view hull of the
  // ellipsoid, a few tenths of a percent above its volume.
  EXPECT_NEAR(away.volume_mm3, at_origin.volume_mm3, 0.005 * at_origin.volume_mm3);
  EXPECT_NEAR(away.length_mm, at_origin.length_mm, 0.02 * at_origin.length_mm);
  EXPECT_GT(away.volume_mm3, seed.volume());
  EXPECT_LT(away.volume_mm3, 1.02 * seed.volume());
}

TEST(HullMeasurement, TheMeshFromTheFineCarveEqualsItsOwnCarve) {
  // At the default resolutions (256, mesh 128) the surface's occupancy fractions come from the fine
  // carve's voxel centres, which are the mesh voxels' 2^3 samples: the same fractions as a carve
  // of the mesh grid with subvoxel_samples = 2 (kept centres plus inside cells at fraction 1).
  const Turntable rig{{6000, 320, 240}, 100, 36, 0.0, 2 * std::numbers::pi / 36, 640, 480};
  const Ellipsoid seed(3.6, 1.45, 1.8);
  const std::vector<View> views = rig.all_views();
  std::vector<Mask> masks;
  for (const View& v : views) masks.push_back(render(seed, v).mask);
  HullOptions options;
  options.keep_occupancy = true;
  const HullMeasurement m = measure_hull(views, masks, options);
  VoxelGrid mesh_grid = m.grid;
  mesh_grid.voxel *= 2;
  for (int a = 0; a < 3; ++a) mesh_grid.n[a] /= 2;
  ASSERT_EQ(m.occupancy.n[0], mesh_grid.n[0] + 2);
  const CarveResult own = carve(views, masks, mesh_grid, {2, true});
  std::vector<float> expected(m.occupancy.values.size(), 0.0f);
  const auto at = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i + 1) +
           m.occupancy.n[0] * (static_cast<std::size_t>(j + 1) + m.occupancy.n[1] * static_cast<std::size_t>(k + 1));
  };
  for (const Block& b : own.inside)
    for (int k = b.k; k < std::min(b.k + b.size, mesh_grid.n[2]); ++k)
      for (int j = b.j; j < std::min(b.j + b.size, mesh_grid.n[1]); ++j)
        for (int i = b.i; i < std::min(b.i + b.size, mesh_grid.n[0]); ++i) expected[at(i, j, k)] = 1.0f;
  for (const BoundaryVoxel& v : own.boundary) expected[at(v.i, v.j, v.k)] = v.fraction;
  // The samples' coordinates are summed in another order on the two paths, so a sample that
  // projects within rounding of a pixel edge may fall the other way: a few in a million.
  std::size_t differ = 0, occupied = 0;
  for (std::size_t c = 0; c < expected.size(); ++c) {
    occupied += expected[c] > 0;
    differ += std::abs(expected[c] - m.occupancy.values[c]) > 1e-6f;
  }
  std::printf("%zu of %zu occupied mesh voxels differ\n", differ, occupied);
  EXPECT_GT(occupied, 100000u);
  EXPECT_LE(differ, occupied / 10000) << differ << " of " << occupied << " occupied voxels differ";
  ScalarField own_field = m.occupancy;
  own_field.values = expected;
  const double own_surface = surface_area(marching_cubes(own_field, 0.5f));
  EXPECT_NEAR(m.surface_mm2, own_surface, 1e-3 * own_surface);
}

}  // namespace
}  // namespace suite::carving
