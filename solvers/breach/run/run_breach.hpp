#pragma once
// The `breach` executable's run: reads the scene, integrates it, and writes into `out`
//   effective_config.yaml   the scene as used, defaults included
//   hydrograph.csv          time series with units (inflow, outflows, level, stage, geometry)
//   summary.json            peak outflow, time to peak, breach initiation time, final width and
//                           depth, eroded volume, failed yes/no, mass balance, step counts
//   run.json                program, version, build, timings
//   hydrographs.png         inflow and outflow hydrographs, level and breach geometry
//                           (plot_breach.py; skipped with a warning if python cannot run it)
// Serial: one process per scene (studies run many scenes, in one process or many).
#include <filesystem>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/io/csv_series.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/run/run_record.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace suite::breach {

struct RunOptions {
  std::filesystem::path out;
  std::vector<std::string> argv;  // for run.json
};

// Returns the exit status. Throws InputError for a bad scene (before anything is written but
// the output folder).
int run_breach(const mpi::Comm& comm, const config::Config& scene, const RunOptions& options, Logger& log);

// The summary.json content of a result (also used by studies that keep summaries in memory).
Summary make_summary(const Result& result);

// hydrograph.csv: its columns, and the row of one sample (also written by foam-erosion's
// breach-model comparison).
const std::vector<io::CsvColumn>& hydrograph_columns();
std::vector<double> hydrograph_row(const Sample& sample);

}  // namespace suite::breach
