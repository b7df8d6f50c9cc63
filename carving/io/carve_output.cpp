#include "carving/io/carve_output.hpp"

#include <fmt/format.h>

#include <span>
#include <string>

#include "core/io/atomic_file.hpp"
#include "core/io/h5_file.hpp"
#include "core/mpi/comm.hpp"

namespace suite::carving {

std::vector<std::uint8_t> occupancy_bytes(const CarveResult& r, const std::vector<std::uint8_t>& initial) {
  const auto& n = r.grid.n;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(r.grid.count()), 0);
  const auto at = [&](int i, int j, int k) {
    return static_cast<std::size_t>(j) + static_cast<std::size_t>(n[1]) * (i + static_cast<std::size_t>(n[0]) * k);
  };
  for_each_kept_voxel(r, [&](int i, int j, int k) { bytes[at(i, j, k)] = 1; });
  if (!initial.empty())
    for (std::size_t m = 0; m < bytes.size(); ++m) bytes[m] = bytes[m] && initial[m];
  return bytes;
}

void write_carve_output(const std::filesystem::path& dir, const VoxelGrid& g, const std::vector<std::uint8_t>& bytes) {
  std::filesystem::create_directories(dir);
  io::write_file_atomic(dir / "voxels.raw", std::string(bytes.begin(), bytes.end()));
  const mpi::Comm self(MPI_COMM_SELF);
  io::H5File file(self, dir / "voxels.h5", io::H5File::Mode::create);
  std::vector<unsigned char> values(bytes.begin(), bytes.end());
  file.write_rows<unsigned char>("/occupancy", std::span<const unsigned char>(values),
                                 static_cast<std::size_t>(g.n[1]));
  file.set_attribute("/occupancy", "shape_zxy", fmt::format("{} {} {}", g.n[2], g.n[0], g.n[1]));
  const Eigen::Vector3d origin = g.centre(0, 0, 0);
  file.set_attribute("/occupancy", "origin_mm_xyz",
                     fmt::format("{:.17g} {:.17g} {:.17g}", origin.x(), origin.y(), origin.z()));
  file.set_attribute("/occupancy", "voxel_mm_xyz",
                     fmt::format("{:.17g} {:.17g} {:.17g}", g.voxel.x(), g.voxel.y(), g.voxel.z()));
  file.close();
}

}  // namespace suite::carving
