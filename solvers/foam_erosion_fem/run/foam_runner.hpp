#pragma once
// Runs OpenFOAM programs (blockMesh, setFields, interFoam, ...) as child processes on one case:
// WM_PROJECT_DIR set (the only variable Debian's package needs), standard output and error into
// one log file per run in the log folder, and the MPI variables of this process removed so a
// decomposed run under mpirun starts cleanly even when foam-erosion itself runs under MPI.
//
// A run fails (FoamRunError) on a non-zero exit, a "FOAM FATAL" in its log, or, while it runs,
// a Courant number past the blow-up limit or NaN in the Courant line (the child is stopped).
// The error names the program, the reason, the last lines of its log, the log and the case.
//
// A stop request (RunnerOptions::stop_requested, e.g. SIGTERM from Slurm) ends a program started
// with `stoppable` (the solver) with SIGTERM, or keeps one from starting, and throws
// FoamRunStopped: the run was asked to end, nothing failed. The short programs that rebuild a
// case (subsetMesh, mapFields, ...) are left to finish, so a stop never leaves half a case; one
// that the same signal killed throws FoamRunStopped too.
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace suite::foam_erosion {

class FoamRunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A program ended (or not started) because the run was asked to stop.
class FoamRunStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunnerOptions {
  std::filesystem::path project_dir;  // WM_PROJECT_DIR; empty: $WM_PROJECT_DIR or /usr/share/openfoam
  double courant_blow_up = 50.0;      // stop a solver whose max Courant number passes this
  int log_tail_lines = 15;            // lines of the log quoted in an error
  // Polled before a stoppable program starts and while it runs; true stops it (SIGTERM) and
  // throws FoamRunStopped. It must keep answering true once it has.
  std::function<bool()> stop_requested;
};

struct ProgramRun {
  std::string program;
  std::filesystem::path log;
  double wall_seconds = 0.0;
  double max_courant = 0.0;  // largest "Courant Number ... max:" seen (solvers only)
  long long time_steps = 0;  // "Time = " lines seen (solvers only)
};

class FoamRunner {
 public:
  // InputError if OpenFOAM is not usable here: the project folder lacks etc/controlDict, or
  // blockMesh/interFoam are not on PATH. The message says how to install or point at it.
  FoamRunner(std::filesystem::path case_dir, std::filesystem::path log_dir, RunnerOptions options = {});

  // Runs `program args... -case <case>` (with -parallel under mpirun when ranks > 1) and waits.
  // `log_name` names the log file (default: the program); a later run with the same name
  // appends a counter rather than overwriting. `stoppable`: a stop request ends it (see above).
  ProgramRun run(const std::string& program, const std::vector<std::string>& args = {}, int ranks = 1,
                const std::string& log_name = "", bool stoppable = false);

  const std::filesystem::path& case_dir() const { return case_dir_; }
  const std::filesystem::path& project_dir() const { return project_dir_; }

 private:
  std::filesystem::path fresh_log_path(const std::string& name) const;

  std::filesystem::path case_dir_, log_dir_, project_dir_;
  RunnerOptions options_;
};

// Where an executable is on PATH, if anywhere.
std::optional<std::filesystem::path> find_on_path(const std::string& program);

}  // namespace suite::foam_erosion
