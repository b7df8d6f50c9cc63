#pragma once
// Shape from silhouette (docs/methods/carving.md): a voxel is kept iff its centre, projected by every
// view and rounded to the nearest pixel, lands on a seed pixel of that view's mask.
//
// carve() is hierarchical: it tests whole cells of voxels against each view at once. The
// projections of a cell's eight corners bound the pixels any point of the cell can land on (the
// image of a box in front of a pinhole or parallel camera is the convex hull of its corners'
// images, and rounding is monotone), and the mask's integral image counts the seed pixels in that
// rectangle: none -> the cell is empty (early exit, no other view is looked at); all -> this view
// keeps the whole cell and is not asked again inside it; otherwise the cell is split in eight.
// Only cells on the silhouette boundary are refined, so the work grows with the seed's surface,
// not its volume, and the voxel count is exactly that of the plain voxel loop.
//
// With subvoxel_samples = s > 0, cells are tested by their full extent, and each voxel the
// silhouette boundary passes through is sampled at s^3 interior points: the sub-voxel volume.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "carving/camera/camera.hpp"
#include "carving/hull/voxel_grid.hpp"
#include "carving/image/mask.hpp"

namespace suite::carving {

struct CarveOptions {
  int subvoxel_samples = 0;  // s: s^3 samples in each boundary voxel; 0 = voxel centres only
  bool keep_cells = false;   // keep the inside blocks and boundary voxels (for meshes and HDF5)
};

// A cube of size^3 voxels starting at voxel (i, j, k), clipped to the grid: every voxel kept.
struct Block {
  int i = 0, j = 0, k = 0, size = 1;
};

// A voxel the silhouette boundary passes through, with the fraction of its samples kept and
// whether its centre is kept.
struct BoundaryVoxel {
  int i = 0, j = 0, k = 0;
  float fraction = 0;
  bool centre_kept = false;
};

struct CarveStats {
  long long cells = 0;        // cells classified (all levels)
  long long view_tests = 0;   // cell-view rectangle tests
  long long point_tests = 0;  // single-point projections (voxel centres and sub-samples)
};

struct CarveResult {
  VoxelGrid grid;
  long long voxels = 0;               // kept voxel centres
  double volume_mm3 = 0;              // voxels x voxel volume
  double subvoxel_volume_mm3 = 0;     // with sub-voxel boundary fractions (= volume_mm3 when s = 0)
  std::array<int, 3> first{0, 0, 0};  // bounding box of kept voxels, inclusive (empty: first > last)
  std::array<int, 3> last{-1, -1, -1};
  std::vector<Block> inside;  // with keep_cells
  std::vector<BoundaryVoxel> boundary;
  CarveStats stats;
};

// Calls f(i, j, k) once for every voxel whose centre a carve made with keep_cells kept: each voxel
// of the inside blocks (clipped to the grid), then the boundary voxels with their centre kept.
template <class F>
void for_each_kept_voxel(const CarveResult& r, F&& f) {
  const auto& n = r.grid.n;
  for (const Block& b : r.inside)
    for (int k = b.k; k < std::min(b.k + b.size, n[2]); ++k)
      for (int j = b.j; j < std::min(b.j + b.size, n[1]); ++j)
        for (int i = b.i; i < std::min(b.i + b.size, n[0]); ++i) f(i, j, k);
  for (const BoundaryVoxel& v : r.boundary)
    if (v.centre_kept) f(v.i, v.j, v.k);
}

// views[v] and masks[v] belong together; each mask has its view's size. Throws InputError when
// the sizes disagree or the grid reaches behind a camera.
CarveResult carve(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid,
                  const CarveOptions& options = {});

// The plain voxel-major loop with early exit (the reference the hierarchy must match voxel for
// voxel, and the benchmark's baseline).
long long carve_plain(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid);

}  // namespace suite::carving
