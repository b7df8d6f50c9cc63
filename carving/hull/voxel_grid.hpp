#pragma once
// The box of space carved for one seed: n[0] x n[1] x n[2] voxels of size `voxel` (mm per axis),
// voxel (0,0,0) starting at corner `lo`. Voxel (i,j,k) has its centre at lo + (idx + 1/2) voxel.
#include <Eigen/Core>
#include <array>

namespace suite::carving {

struct VoxelGrid {
  Eigen::Vector3d lo{0, 0, 0};
  Eigen::Vector3d voxel{1, 1, 1};
  std::array<int, 3> n{0, 0, 0};

  Eigen::Vector3d centre(int i, int j, int k) const {
    return lo + Eigen::Vector3d((i + 0.5) * voxel.x(), (j + 0.5) * voxel.y(), (k + 0.5) * voxel.z());
  }
  double voxel_volume() const { return voxel.x() * voxel.y() * voxel.z(); }
  long long count() const { return static_cast<long long>(n[0]) * n[1] * n[2]; }

  // A cube of side `side` (mm) centred on `centre`, cut into `cells` voxels per axis.
  static VoxelGrid cube(const Eigen::Vector3d& centre, double side, int cells) {
    VoxelGrid g;
    g.lo = centre - Eigen::Vector3d::Constant(side / 2);
    g.voxel = Eigen::Vector3d::Constant(side / cells);
    g.n = {cells, cells, cells};
    return g;
  }
};

}  // namespace suite::carving
