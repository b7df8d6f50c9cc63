#pragma once
// What was built: filled in by CMake (build_info.cpp.in) and the git hash of the source tree
// at build time (cmake/GitHash.cmake), for run.json and checkpoint headers.
#include <string>

namespace suite {

struct BuildInfo {
  std::string version;     // project version, e.g. "0.1.0"
  std::string git_hash;    // "unknown" outside a git checkout; "+dirty" when uncommitted changes
  std::string build_type;  // Release, Debug, RelWithDebInfo
  std::string compiler;    // e.g. "GNU 12.2.0"
  std::string cxx_flags;   // flags of the build type
  std::string mpi;         // MPI library version string
};

BuildInfo build_info();

}  // namespace suite
