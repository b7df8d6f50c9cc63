#include "core/mpi/environment.hpp"

#include <fmt/format.h>
#include <mpi.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace suite::mpi {
namespace {
int to_mpi(ThreadLevel t) {
  switch (t) {
    case ThreadLevel::single:
      return MPI_THREAD_SINGLE;
    case ThreadLevel::funneled:
      return MPI_THREAD_FUNNELED;
    case ThreadLevel::serialized:
      return MPI_THREAD_SERIALIZED;
    case ThreadLevel::multiple:
      return MPI_THREAD_MULTIPLE;
  }
  return MPI_THREAD_SINGLE;
}
ThreadLevel from_mpi(int t) {
  if (t >= MPI_THREAD_MULTIPLE) return ThreadLevel::multiple;
  if (t >= MPI_THREAD_SERIALIZED) return ThreadLevel::serialized;
  if (t >= MPI_THREAD_FUNNELED) return ThreadLevel::funneled;
  return ThreadLevel::single;
}

// True when a launcher started this process (Open MPI's mpirun, or a PMI/PMIx launcher such as
// srun): its variables are in the environment.
bool launched() {
  for (const char* name : {"OMPI_UNIVERSE_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

constexpr const char* kSessionPrefix = "suite-mpi.";

// Removes the session folders (suite-mpi.PID.XXXXXX) that killed singletons left in `base`: those
// whose process no longer exists. A folder whose PID a live process has taken again stays.
void remove_stale_session_dirs(const std::filesystem::path& base) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(base, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kSessionPrefix, 0) != 0) continue;
    const std::string rest = name.substr(std::string(kSessionPrefix).size());
    const auto dot = rest.find('.');
    if (dot == std::string::npos || dot == 0 || rest.find_first_not_of("0123456789") != dot) continue;
    struct stat info {};
    if (::stat(entry.path().c_str(), &info) != 0 || info.st_uid != ::getuid()) continue;
    if (::kill(static_cast<pid_t>(std::stol(rest.substr(0, dot))), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    std::filesystem::remove_all(entry.path(), ignored);
  }
}

// A new empty folder for one singleton's Open MPI session files ("" if none can be made, and the
// singleton then starts Open MPI's daemon as before): isolated singletons running at once on one
// machine would otherwise share one session folder and its MPI-IO shared-file-pointer files.
std::string private_session_dir() {
  std::error_code ec;
  std::filesystem::path base = std::filesystem::temp_directory_path(ec);
  if (ec) return "";
  remove_stale_session_dirs(base);
  std::string pattern = (base / (kSessionPrefix + std::to_string(::getpid()) + ".XXXXXX")).string();
  if (!mkdtemp(pattern.data())) return "";
  return pattern;
}
}  // namespace

Environment::Environment(int& argc, char**& argv, ThreadLevel required) {
  int initialised = 0;
  SUITE_MPI_CHECK(MPI_Initialized(&initialised));
  int provided = MPI_THREAD_SINGLE;
  if (initialised) {
    SUITE_MPI_CHECK(MPI_Query_thread(&provided));
  } else {
    // Set for this process's MPI_Init only, then taken out again, so that programs it starts
    // (a study's evaluations, foam-erosion's mpirun) see the environment it was given.
    std::vector<std::pair<std::string, std::string>> settings;
    if (!launched()) {
      settings.emplace_back("OMPI_MCA_pml", "ob1");
      if (!std::getenv("OMPI_MCA_ess_singleton_isolated") && !std::getenv("OMPI_MCA_orte_tmpdir_base")) {
        session_dir_ = private_session_dir();
        if (!session_dir_.empty()) {
          settings.emplace_back("OMPI_MCA_ess_singleton_isolated", "1");
          settings.emplace_back("OMPI_MCA_orte_tmpdir_base", session_dir_);
        }
      }
    }
    std::vector<std::string> set;
    for (const auto& [name, value] : settings)
      if (!std::getenv(name.c_str())) setenv(name.c_str(), value.c_str(), 1), set.push_back(name);
    SUITE_MPI_CHECK(MPI_Init_thread(&argc, &argv, to_mpi(required), &provided));
    for (const auto& name : set) unsetenv(name.c_str());
    owns_ = true;
  }
  provided_ = from_mpi(provided);
  if (provided < to_mpi(required)) {
    throw LibraryError(fmt::format("MPI provides thread level {} but {} was required", provided, to_mpi(required)));
  }
}

Environment::~Environment() {
  if (!owns_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
  if (!session_dir_.empty()) {
    std::error_code ignored;  // a folder left behind in the temporary folder is harmless
    std::filesystem::remove_all(session_dir_, ignored);
  }
}

}  // namespace suite::mpi
