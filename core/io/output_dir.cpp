#include "core/io/output_dir.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include "core/errors.hpp"

namespace suite::io {

std::filesystem::path prepare_output_dir(const mpi::Comm& comm, const std::filesystem::path& dir) {
  std::string problem;
  if (comm.is_root()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      problem = ec.message();
    } else if (!std::filesystem::is_directory(dir)) {
      problem = "it exists and is not a folder";
    } else if (::access(dir.c_str(), W_OK) != 0) {
      problem = "it is not writable";
    }
  }
  comm.broadcast(problem, 0);
  if (!problem.empty()) {
    throw InputError(
        fmt::format("cannot use output folder '{}': {}; choose another with --out", dir.string(), problem));
  }
  return std::filesystem::absolute(dir);
}

}  // namespace suite::io
