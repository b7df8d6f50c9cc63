#pragma once
// Reader for `carve_input.dat`, the binary input of the Kansas State multithreaded carving
// program (data/kstate_wheat_36view/README.md), little-endian:
//   3 x int32 grid size; nx*ny*nz bytes of initial occupancy; int32 view count m; then per view
//   12 x float64 P (3 x 4, column-major), 2 x int32 mask width and height, width*height mask
//   bytes stored x-major (index x * height + y); finally 3 x float64 size of the voxel box (mm).
// The box is centred on the world origin and its cells' centres sit at (i + 1/2) size/n - size/2
// (`grid`). The original program tests voxel i one voxel further, at (i + 3/2) size/n - size/2 (its
// loop adds one voxel to the first centre), and that is the voxel its initial-occupancy byte i and
// its output byte i belong to (`original`).
#include <filesystem>
#include <vector>

#include "carving/camera/camera.hpp"
#include "carving/hull/voxel_grid.hpp"
#include "carving/image/mask.hpp"

namespace suite::carving {

struct CarveInput {
  VoxelGrid grid;                     // the box's cells
  VoxelGrid original;                 // the positions the original program tests: grid moved by one voxel
  std::vector<std::uint8_t> initial;  // nx*ny*nz initial occupancy bytes, as stored (iy + ny (ix + nx iz))
  std::vector<View> views;
  std::vector<Mask> masks;
  Eigen::Vector3d box_mm{0, 0, 0};
};

// Throws InputError naming the file and the field when it is short, or a size is implausible.
CarveInput read_carve_input(const std::filesystem::path& file);

}  // namespace suite::carving
