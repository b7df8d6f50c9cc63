#pragma once
// A foam-erosion run from a scene, into one output folder:
//   case/             the OpenFOAM case (time directories, postProcessing/, polyMesh)
//   logs/             one log per OpenFOAM program run (log.blockMesh, log.interFoam.3, ...)
//   discharge.csv     Q(t) through the inlet, crest, toe and outlet sections, per flow step (m^3/s
//                     over the whole crest length, water only)
//   erosion.csv       per coupling step: time, eroded area, eroded volume, deepest erosion, ...
//   profiles.csv      the dam surface nodes after each coupling step
//   summary.json, run.json, effective_config.yaml
//   state.json        the restart state after the last finished coupling step
// `case_only` stops after the meshed case is written. A fresh run removes the case, cases/ and
// state.json an earlier run left in the folder.
#include <filesystem>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"

namespace suite::foam_erosion {

struct RunOptions {
  std::filesystem::path out;
  bool case_only = false;
  // Go on from the output folder's state.json (the last finished coupling step) instead of
  // starting at t = 0; any value does ("latest" is what the suite's --restart says).
  bool restart = false;
  std::vector<std::string> argv;  // for run.json
};

// Returns the process exit code. Not collective: runs on one process and starts OpenFOAM's.
int run_foam_erosion(const config::Config& scene, const RunOptions& options, Logger& log);

}  // namespace suite::foam_erosion
