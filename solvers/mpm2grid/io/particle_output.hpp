#pragma once
// Particles of both species to one HDF5 file per output step, listed in an XDMF series that
// ParaView opens (core/io/h5_file.hpp, core/io/xdmf.hpp). Per species group (/water, /soil):
// position (rows x 3, z = 0 in 2D), velocity (rows x 3), and pressure (water, Pa) or saturation
// (soil). COLLECTIVE over comm; the XDMF series is written by rank 0 only (nullptr elsewhere).
#include <filesystem>

#include "core/io/xdmf.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {

template <int Dim>
void write_particles(const mpi::Comm& comm, const Simulation<Dim>& simulation, const std::filesystem::path& out,
                     const std::string& file_name, io::XdmfSeries* series);

}  // namespace suite::mpm2grid
