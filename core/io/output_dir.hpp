#pragma once
// The one output folder of a run. COLLECTIVE: rank 0 creates it; every rank learns whether
// that worked, so a bad path is one clear InputError on every rank, never a hang.
#include <filesystem>

#include "core/mpi/comm.hpp"

namespace suite::io {

std::filesystem::path prepare_output_dir(const mpi::Comm& comm, const std::filesystem::path& dir);

}  // namespace suite::io
