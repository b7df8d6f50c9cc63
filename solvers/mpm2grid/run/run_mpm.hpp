#pragma once
// An mpm2grid run from a scene: seeds the particles, steps to time.end with the adaptive dt, and
// writes into the output folder series.csv (time series with units: masses, the inflow, the
// outflow discharges, the eroded soil volume and crest height, io/dam_measures.hpp), profiles.csv
// (the crest profile at every output time), particles/step_NNNNNN.h5 +
// particles.xmf (ParaView), summary.json, run.json, effective_config.yaml, log.txt and
// checkpoints/ (every checkpoint.every_steps steps or checkpoint.every of wall time, on SIGUSR1,
// and on SIGTERM/SIGINT before stopping; a restart continues bit for bit on the same rank count).
// A non-finite particle state stops the run with the step, time, dt and its limiter, keeping the
// last good checkpoint.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"

namespace suite::mpm2grid {

struct RunOptions {
  std::filesystem::path out;
  std::optional<std::string> restart;  // "latest" or a checkpoint file: continue from it
  std::vector<std::string> argv;  // for run.json
};

// COLLECTIVE over comm. Returns the process exit code.
int run_mpm(const mpi::Comm& comm, const config::Config& scene, const RunOptions& options, Logger& log);

}  // namespace suite::mpm2grid
