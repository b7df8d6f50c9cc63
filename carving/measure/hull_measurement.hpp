#pragma once
// One seed's size from its silhouettes (docs/methods/carving.md, multi-view volume carving), modelling no
// more space than the seed fills:
//   1. a coarse carve of the region every camera sees finds the seed's bounding box;
//   2. the box is carved at `resolution` voxels along its longest side (hierarchically, so the
//      work follows the surface), optionally with sub-voxel samples at the boundary;
//   3. length, width and thickness are the seed's extents along the principal axes of the kept
//      volume (longest first);
//   4. optionally a marching-cubes surface of the occupancy fractions at `mesh_resolution` gives
//      the surface area and a PLY mesh. The fractions are those of 2^3 samples per mesh voxel;
//      when `resolution` is twice `mesh_resolution` (the defaults), step 2's grid is the mesh
//      grid halved and its voxel centres are those samples, so no further carve is made.
#include <optional>

#include "carving/camera/camera.hpp"
#include "carving/hull/carver.hpp"
#include "carving/image/mask.hpp"
#include "carving/mesh/marching_cubes.hpp"
#include "carving/mesh/surface_mesh.hpp"

namespace suite::carving {

struct HullOptions {
  int resolution = 256;        // voxels along the longest side of the seed's box
  int subvoxel_samples = 0;    // s^3 samples in boundary voxels (0: voxel centres)
  int search_resolution = 48;  // voxels per side of the coarse search carve
  // The searched cube; default: centred where the views' silhouettes meet (silhouette_centre),
  // as large as the smallest image shows at that point.
  std::optional<Eigen::Vector3d> search_centre;
  std::optional<double> search_side_mm;
  bool mesh = true;
  int mesh_resolution = 128;    // voxels along the longest side for the surface
  bool keep_occupancy = false;  // keep the occupancy fractions the mesh is made from (HDF5 output)
};

struct HullMeasurement {
  double volume_mm3 = 0;  // sub-voxel volume when subvoxel_samples > 0, else kept voxels x voxel volume
  long long voxels = 0;   // kept voxel centres at `resolution`
  double length_mm = 0, width_mm = 0, thickness_mm = 0;
  double surface_mm2 = 0;                              // NaN without a mesh
  VoxelGrid grid;                                      // the carved box
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // principal axes (columns: length, width, thickness)
  SurfaceMesh mesh;
  ScalarField occupancy;  // at mesh_resolution, when options.keep_occupancy (and mesh)
  CarveStats stats;       // of the fine carve
  // Per view, the part of its silhouette the hull's image covers (measure/silhouette_agreement.hpp),
  // from a carve of the seed's box at kAgreementResolution voxels along its longest side.
  std::vector<double> coverage;
  double coverage_s = 0;  // wall time of that check, s
};

inline constexpr int kAgreementResolution = 64;

// Throws InputError when no voxel survives (the silhouettes and cameras do not agree), or the
// seed touches the searched region's border or its own carving box's (it may be cut off).
HullMeasurement measure_hull(const std::vector<View>& views, const std::vector<Mask>& masks,
                             const HullOptions& options);

// The cube measure_hull() searches for the seed: options.search_side_mm and search_centre, by
// default centred on `centre` and as large as the smallest image shows there, with `resolution`
// voxels per side.
VoxelGrid search_cube(const std::vector<View>& views, const HullOptions& options, int resolution,
                      const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

// The point nearest (least squares) to the lines of sight through every silhouette's centroid:
// where the seed is, whatever world frame the cameras are calibrated in (a projection-matrix set
// need not put the seed at its origin). The world origin when the lines do not fix a point (one
// view, or all views along one direction).
Eigen::Vector3d silhouette_centre(const std::vector<View>& views, const std::vector<Mask>& masks);

// Pixels per mm at the point X in `view` (at the world origin: the scale of a turntable's axis).
double pixels_per_mm_at(const View& view, const Eigen::Vector3d& X = Eigen::Vector3d::Zero());

}  // namespace suite::carving
