#pragma once
// The demo run: samples Ritter's solution on a line of cells split over the ranks of `comm`,
// integrates the outflow at the channel end in time, checks the water balance each sample,
// and writes the suite's standard outputs into `out`:
//   effective_config.yaml, run.json, summary.json, discharge.csv (time series with units),
//   fields/step_NNNNNN.h5 + dam_break.xmf (ParaView), checkpoints/checkpoint_NNNNNNNNN.h5.
// COLLECTIVE over `comm`. Throws InputError for bad scenes.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"

namespace suite::demo {

struct DamBreakOptions {
  std::filesystem::path out;
  std::optional<std::string> restart;  // checkpoint file or "latest"
  std::vector<std::string> argv;       // for run.json
};

// Returns the process exit status: 0 when the run reached time.end or stopped cleanly.
int run_dam_break(const mpi::Comm& comm, const config::Config& scene, const DamBreakOptions& options, Logger& log);

}  // namespace suite::demo
