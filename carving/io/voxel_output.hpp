#pragma once
// A seed's voxel result as HDF5 (issue 4: "voxel result optionally as HDF5"), for users who
// analyse the shape further (h5py, ParaView's HDF5 reader, MATLAB).
//
// voxels.h5 holds /occupancy: the fraction of each voxel inside the visual hull (float32, 0..1,
// from 2^3 samples per boundary voxel; 0 and 1 away from the surface), stored as a 2D dataset of
// (nz * ny) rows by nx columns, i fastest, with one empty layer all round (the grid the surface
// mesh was made from). Attributes on /occupancy: shape_zyx "nz ny nx", origin_mm_xyz (the centre of
// voxel (0, 0, 0)) and voxel_mm; world axes as in the profile's camera calibration (y along the
// turntable axis, image down). volume = sum(occupancy) * voxel_mm^3.
#include <filesystem>

#include "carving/mesh/marching_cubes.hpp"

namespace suite::carving {

// Written by this process alone (its own MPI_COMM_SELF file), so any rank of a batch may call it.
void write_occupancy_h5(const std::filesystem::path& path, const ScalarField& occupancy);

}  // namespace suite::carving
