#include "carving/io/voxel_output.hpp"

#include <span>

#include <fmt/format.h>

#include "core/io/h5_file.hpp"
#include "core/mpi/comm.hpp"

namespace suite::carving {

void write_occupancy_h5(const std::filesystem::path& path, const ScalarField& f) {
  const mpi::Comm self(MPI_COMM_SELF);
  io::H5File file(self, path, io::H5File::Mode::create);
  file.write_rows<float>("/occupancy", std::span<const float>(f.values), static_cast<std::size_t>(f.n[0]));
  file.set_attribute("/occupancy", "shape_zyx", fmt::format("{} {} {}", f.n[2], f.n[1], f.n[0]));
  file.set_attribute("/occupancy", "origin_mm_xyz", fmt::format("{:.17g} {:.17g} {:.17g}", f.origin.x(), f.origin.y(), f.origin.z()));
  file.set_attribute("/occupancy", "voxel_mm", f.spacing);
  file.close();
}

}  // namespace suite::carving
