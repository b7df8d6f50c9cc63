#include "carving/measure/hull_measurement.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "carving/measure/silhouette_agreement.hpp"
#include "carving/mesh/marching_cubes.hpp"
#include "core/errors.hpp"

namespace suite::carving {
namespace {

// Cubic voxels covering [lo, hi], `resolution` of them along the longest side, centred on the box.
VoxelGrid box_grid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int resolution) {
  const Eigen::Vector3d size = hi - lo;
  const double voxel = size.maxCoeff() / resolution;
  VoxelGrid g;
  g.voxel = Eigen::Vector3d::Constant(voxel);
  for (int a = 0; a < 3; ++a) g.n[a] = std::max(1, static_cast<int>(std::ceil(size[a] / voxel - 1e-9)));
  const Eigen::Vector3d covered(g.n[0] * voxel, g.n[1] * voxel, g.n[2] * voxel);
  g.lo = (lo + hi) / 2 - covered / 2;
  return g;
}

// Kept volume as weighted boxes: (first voxel, last voxel, weight per voxel).
struct WeightedBox {
  std::array<int, 3> first, last;
  double weight;
};

std::vector<WeightedBox> kept_boxes(const CarveResult& r) {
  std::vector<WeightedBox> boxes;
  for (const Block& b : r.inside)
    boxes.push_back({{b.i, b.j, b.k},
                     {std::min(b.i + b.size, r.grid.n[0]) - 1, std::min(b.j + b.size, r.grid.n[1]) - 1,
                      std::min(b.k + b.size, r.grid.n[2]) - 1},
                     1.0});
  for (const BoundaryVoxel& v : r.boundary)  // fraction 1 for kept centres without sub-samples
    if (v.fraction > 0) boxes.push_back({{v.i, v.j, v.k}, {v.i, v.j, v.k}, v.fraction});
  return boxes;
}

// Principal axes of the kept volume and the extents along them (longest first).
void principal_dimensions(const CarveResult& r, HullMeasurement& m) {
  const auto boxes = kept_boxes(r);
  const VoxelGrid& g = r.grid;
  double volume = 0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();
  for (const auto& b : boxes) {
    const Eigen::Vector3d lo = g.lo + Eigen::Vector3d(b.first[0], b.first[1], b.first[2]).cwiseProduct(g.voxel);
    const Eigen::Vector3d hi =
        g.lo + Eigen::Vector3d(b.last[0] + 1, b.last[1] + 1, b.last[2] + 1).cwiseProduct(g.voxel);
    const Eigen::Vector3d size = hi - lo, c = (lo + hi) / 2;
    const double v = size.prod() * b.weight;
    volume += v;
    first_moment += v * c;
    second_moment += v * (c * c.transpose());
    second_moment.diagonal() += v * size.cwiseAbs2() / 12.0;  // a uniform box about its centre
  }
  const Eigen::Vector3d centroid = first_moment / volume;
  const Eigen::Matrix3d covariance = second_moment / volume - centroid * centroid.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  // Eigen sorts eigenvalues ascending: the longest axis is the last.
  for (int a = 0; a < 3; ++a) m.axes.col(a) = eigen.eigenvectors().col(2 - a);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& b : boxes)
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner =
          g.lo + Eigen::Vector3d((c & 1) ? b.last[0] + 1 : b.first[0], (c & 2) ? b.last[1] + 1 : b.first[1],
                                 (c & 4) ? b.last[2] + 1 : b.first[2])
                     .cwiseProduct(g.voxel);
      const Eigen::Vector3d p = m.axes.transpose() * (corner - centroid);
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  m.length_mm = hi[0] - lo[0];
  m.width_mm = hi[1] - lo[1];
  m.thickness_mm = hi[2] - lo[2];
}

// Zero fractions at the centres of `g`'s voxels with one empty layer all round, and the index of
// voxel (i, j, k) of `g` in it.
ScalarField padded_field(const VoxelGrid& g) {
  ScalarField f;
  f.n = {g.n[0] + 2, g.n[1] + 2, g.n[2] + 2};
  f.spacing = g.voxel.x();
  f.origin = g.lo + g.voxel / 2 - g.voxel;
  f.values.assign(static_cast<std::size_t>(f.n[0]) * f.n[1] * f.n[2], 0.0f);
  return f;
}
std::size_t padded_index(const ScalarField& f, int i, int j, int k) {
  return static_cast<std::size_t>(i + 1) + f.n[0] * (static_cast<std::size_t>(j + 1) + f.n[1] * (k + 1));
}

// The occupancy fractions of a carve at voxel centres, with one empty layer all round.
ScalarField occupancy_field(const CarveResult& r) {
  ScalarField f = padded_field(r.grid);
  for (const auto& b : kept_boxes(r))
    for (int k = b.first[2]; k <= b.last[2]; ++k)
      for (int j = b.first[1]; j <= b.last[1]; ++j)
        for (int i = b.first[0]; i <= b.last[0]; ++i) f.values[padded_index(f, i, j, k)] = static_cast<float>(b.weight);
  return f;
}

// The occupancy fractions at `coarse` voxel centres, with one empty layer all round, from a carve
// (with keep_cells) on `coarse` halved: each coarse voxel's fraction is the share of its 2^3 fine
// voxel centres kept, which are the 2^3 samples a carve of `coarse` with subvoxel_samples = 2
// would test.
ScalarField occupancy_of_halves(const CarveResult& fine, const VoxelGrid& coarse) {
  ScalarField f = padded_field(coarse);
  for_each_kept_voxel(fine, [&](int i, int j, int k) { f.values[padded_index(f, i / 2, j / 2, k / 2)] += 0.125f; });
  return f;
}

// `g` with voxels of half the size over the same box.
VoxelGrid halved(const VoxelGrid& g) {
  VoxelGrid h = g;
  h.voxel = g.voxel / 2;
  for (int a = 0; a < 3; ++a) h.n[a] = 2 * g.n[a];
  return h;
}

}  // namespace

double pixels_per_mm_at(const View& view, const Eigen::Vector3d& X) {
  const Eigen::Vector2d o = project(view.P, X);
  const Eigen::Vector2d y = project(view.P, X + Eigen::Vector3d(0, 1e-3, 0));
  return (y - o).norm() / 1e-3;
}

VoxelGrid search_cube(const std::vector<View>& views, const HullOptions& options, int resolution,
                      const Eigen::Vector3d& centre) {
  const Eigen::Vector3d at = options.search_centre.value_or(centre);
  double side = std::numeric_limits<double>::infinity();
  for (const View& v : views) side = std::min(side, std::min(v.width, v.height) / pixels_per_mm_at(v, at));
  if (options.search_side_mm) side = *options.search_side_mm;
  return VoxelGrid::cube(at, side, resolution);
}

Eigen::Vector3d silhouette_centre(const std::vector<View>& views, const std::vector<Mask>& masks) {
  // Each line of sight through pixel (u, v) is where two planes meet:
  //   (P_0 - u P_2) X = 0 and (P_1 - v P_2) X = 0 (X homogeneous), for pinhole and parallel views.
  // The point minimising the squared distances to all the planes (each normalised).
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < views.size(); ++k) {
    const Mask& m = masks[k];
    double sx = 0, sy = 0;
    long long n = 0;
    const Mask::Box box = m.seed_box();
    for (int y = box.y0; y <= box.y1; ++y)
      for (int x = box.x0; x <= box.x1; ++x)
        if (m.at(x, y)) sx += x, sy += y, ++n;
    if (n == 0) continue;
    const Eigen::Vector2d c(sx / static_cast<double>(n), sy / static_cast<double>(n));
    const Projection& P = views[k].P;
    for (int r = 0; r < 2; ++r) {
      const Eigen::Matrix<double, 1, 4> plane = P.row(r) - c[r] * P.row(2);
      const double norm = plane.head<3>().norm();
      if (!(norm > 0)) continue;
      const Eigen::Vector3d a = plane.head<3>().transpose() / norm;
      AtA += a * a.transpose();
      Atb += a * (-plane(3) / norm);
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(AtA);
  if (!(eigen.eigenvalues()[0] > 1e-9 * std::max(1.0, eigen.eigenvalues()[2]))) return Eigen::Vector3d::Zero();
  return AtA.ldlt().solve(Atb);
}

HullMeasurement measure_hull(const std::vector<View>& views, const std::vector<Mask>& masks,
                             const HullOptions& options) {
  if (options.resolution < 4 || options.resolution > 4096)
    throw InputError(fmt::format("carving.resolution = {}: give 4 to 4096 voxels along the seed", options.resolution));
  if (options.search_resolution < 8 || options.search_resolution > 512)
    throw InputError(fmt::format("carving.search_resolution = {}: give 8 to 512", options.search_resolution));
  if (views.empty()) throw InputError("carving needs at least one view");
  // 1. Find the seed in the region all cameras see.
  const VoxelGrid search = search_cube(views, options, options.search_resolution, silhouette_centre(views, masks));
  const double side = search.voxel.x() * search.n[0];
  const CarveResult coarse = carve(views, masks, search);
  if (coarse.voxels == 0)
    throw InputError(
        fmt::format("no voxel of the {:.3g} mm search cube survives carving with {} views: the "
                    "silhouettes and the camera calibration do not agree (check the camera "
                    "distance, the angles and where the calibrated image sits in the photographs), "
                    "or the search voxels ({:.3g} mm) may be thicker than the seed (give a finer "
                    "carving.search_resolution or a smaller carving.search_side)",
                    side, views.size(), search.voxel.x()));
  for (int a = 0; a < 3; ++a)
    if (coarse.first[a] == 0 || coarse.last[a] == search.n[a] - 1)
      throw InputError(
          fmt::format("the seed reaches the border of the {:.3g} mm search cube (axis {}): it may be "
                      "cut off; give carving.search_side larger than the seed",
                      side, "xyz"[a]));
  // 2. The seed's box, one coarse voxel of margin all round, at the requested resolution.
  const Eigen::Vector3d lo =
      search.lo +
      Eigen::Vector3d(coarse.first[0] - 1, coarse.first[1] - 1, coarse.first[2] - 1).cwiseProduct(search.voxel);
  const Eigen::Vector3d hi =
      search.lo +
      Eigen::Vector3d(coarse.last[0] + 2, coarse.last[1] + 2, coarse.last[2] + 2).cwiseProduct(search.voxel);
  HullMeasurement m;
  // With the mesh at half the carve's resolution (the defaults), the carve's grid is the mesh
  // grid with its voxels halved: its voxel centres are then the mesh voxels' 2^3 samples, and the
  // surface needs no carve of its own (a third of the measurement's time).
  const bool mesh_from_fine = options.mesh && options.resolution == 2 * options.mesh_resolution;
  const VoxelGrid mesh_grid = box_grid(lo, hi, options.mesh_resolution);
  m.grid = mesh_from_fine ? halved(mesh_grid) : box_grid(lo, hi, options.resolution);
  const CarveResult fine = carve(views, masks, m.grid, {options.subvoxel_samples, true});
  for (int a = 0; a < 3; ++a)
    if (fine.voxels > 0 && (fine.first[a] == 0 || fine.last[a] == m.grid.n[a] - 1))
      throw InputError(
          fmt::format("the seed's hull reaches the border of its {:.3g} x {:.3g} x {:.3g} mm carving box "
                      "(axis {}): it is cut off there; the coarse search (carving.search_resolution = "
                      "{}) missed part of the seed, give a finer one",
                      m.grid.n[0] * m.grid.voxel.x(), m.grid.n[1] * m.grid.voxel.y(), m.grid.n[2] * m.grid.voxel.z(),
                      "xyz"[a], options.search_resolution));
  const auto check_start = std::chrono::steady_clock::now();
  m.coverage =
      silhouette_coverage(views, masks, carve(views, masks, box_grid(lo, hi, kAgreementResolution), {0, true}));
  m.coverage_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - check_start).count();
  m.voxels = fine.voxels;
  m.volume_mm3 = fine.subvoxel_volume_mm3;
  m.stats = fine.stats;
  principal_dimensions(fine, m);
  // 4. The surface, from occupancy fractions (2^3 samples per boundary voxel) at mesh resolution.
  m.surface_mm2 = std::nan("");
  if (options.mesh) {
    ScalarField occupancy = mesh_from_fine ? occupancy_of_halves(fine, mesh_grid)
                                           : occupancy_field(carve(views, masks, mesh_grid, {2, true}));
    m.mesh = marching_cubes(occupancy, 0.5f);
    m.surface_mm2 = surface_area(m.mesh);
    if (options.keep_occupancy) m.occupancy = std::move(occupancy);
  }
  return m;
}

}  // namespace suite::carving
