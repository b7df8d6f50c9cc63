#pragma once
// The main of a scene-driven solver executable, once for all of them: MPI up, the command line
// parsed (rank 0 prints --help and usage errors), the logger, the scene (the file given, or the
// executable's embedded default) with the command line's overrides, and the error policy of
// guarded_main around the run.
//
//   int main(int argc, char** argv) {
//     return suite::cli::solver_main(argc, argv, {spec, suite::embedded::x_default_yaml, "x.yaml"},
//                                    [](const suite::cli::SolverRun& r) { return run_x(r.world, r.scene(), ...); });
//   }
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/cli/command_line.hpp"
#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"

namespace suite::cli {

struct SolverProgram {
  // A constructor rather than an aggregate: GCC 12 warns (wrongly) of uninitialised strings in
  // a nested aggregate initialisation of Spec.
  SolverProgram(Spec s, const char* scene, std::string scene_file)
      : spec(std::move(s)), default_scene(scene), default_scene_file(std::move(scene_file)) {}

  Spec spec;                       // program name, description, --out default, --dakota offered
  const char* default_scene;       // the embedded scene's YAML text
  std::string default_scene_file;  // its file name, for messages ("water_column_collapse.yaml")
};

// What a solver's run gets from solver_main.
struct SolverRun {
  const mpi::Comm& world;
  const CommandLine& command_line;
  Logger& log;
  const SolverProgram& program;

  // The scene with these overrides (the command line's by default): the scene file given, else
  // the embedded default.
  config::Config scene(const std::vector<std::string>& overrides) const;
  config::Config scene() const { return scene(command_line.overrides); }

  // --dakota PARAMS RESULTS: each evaluation runs `run_once` on the scene with the parameters'
  // overrides into the output folder and answers with the summary.json it wrote; it fails when
  // `run_once` returns non-zero or the summary's "status", if it has one, is not "finished".
  // Returns the exit status. COLLECTIVE.
  int dakota_driver(const std::function<int(const config::Config& scene)>& run_once) const;
};

// Returns the exit status: 0, 2 for a usage or input error (one line), 1 for an internal error.
int solver_main(int argc, char** argv, const SolverProgram& program, const std::function<int(const SolverRun&)>& run);

}  // namespace suite::cli
