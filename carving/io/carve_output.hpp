#pragma once
// What `seedcarve carve` writes for a carve_input.dat file (docs/carving.md, "Running it"):
//   voxels.raw  one byte per voxel (1 kept, 0 carved), index iy + ny (ix + nx iz): the layout of
//               the original Kansas State program's output file, byte for byte;
//   voxels.h5   /occupancy, the same bytes as a uint8 dataset of nz * nx rows by ny columns
//               (y fastest), with attributes shape_zxy "nz nx ny", origin_mm_xyz (the centre of
//               voxel (0, 0, 0)) and voxel_mm_xyz.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "carving/hull/carver.hpp"

namespace suite::carving {

// The kept voxels of a carve made with keep_cells, as bytes in the original's layout, each also
// cleared where `initial` (the same layout and size, or empty for all ones) is 0.
std::vector<std::uint8_t> occupancy_bytes(const CarveResult& result, const std::vector<std::uint8_t>& initial);

// voxels.raw and voxels.h5 in `dir` (created).
void write_carve_output(const std::filesystem::path& dir, const VoxelGrid& grid,
                        const std::vector<std::uint8_t>& bytes);

}  // namespace suite::carving
