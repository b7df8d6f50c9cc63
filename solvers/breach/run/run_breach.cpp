#include "solvers/breach/run/run_breach.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "core/errors.hpp"
#include "core/io/csv_series.hpp"
#include "core/io/output_dir.hpp"
#include "core/run/phase_timers.hpp"
#include "solvers/breach/io/plot_command.hpp"

namespace suite::breach {

namespace {

const std::vector<io::CsvColumn> kColumns = {{"time", "s"},
                                             {"inflow", "m^3/s"},
                                             {"outflow", "m^3/s"},
                                             {"breach_outflow", "m^3/s"},
                                             {"crest_outflow", "m^3/s"},
                                             {"spillway_outflow", "m^3/s"},
                                             {"level", "m"},
                                             {"storage", "m^3"},
                                             {"stage", ""},
                                             {"stress", "Pa"},
                                             {"face_erosion", "m"},
                                             {"headcut_position", "m"},
                                             {"headcut_height", "m"},
                                             {"invert", "m"},
                                             {"bottom_width", "m"},
                                             {"top_width", "m"},
                                             {"eroded_volume", "m^3"}};

double or_nan(const std::optional<double>& v) {
  return v ? *v : std::nan("");
}

}  // namespace

const std::vector<io::CsvColumn>& hydrograph_columns() {
  return kColumns;
}

std::vector<double> hydrograph_row(const Sample& s) {
  const Flows& f = s.flows;
  return {s.time,           f.inflow,       f.total(),
          f.breach,         f.crest,        f.spillway,
          f.level,          f.storage,      static_cast<double>(static_cast<int>(s.stage)),
          s.stress,         s.face_erosion, s.headcut_position,
          s.headcut_height, s.invert,       s.bottom_width,
          s.top_width,      s.eroded_volume};
}

Summary make_summary(const Result& r) {
  Summary s;
  s.set("peak_outflow", r.peak_outflow, "m^3/s");
  s.set("time_to_peak", r.time_to_peak, "s");
  s.set("peak_breach_outflow", r.peak_breach_outflow, "m^3/s");
  s.set("event_finished", !r.rising_at_end);  // false: the outflow still rises at time.end
  s.set("failed", r.failed());
  s.set("breach_initiation_time", or_nan(r.initiation_time), "s");  // null: no breach
  s.set("headcut_formation_time", or_nan(r.headcut_formation_time), "s");
  s.set("foundation_time", or_nan(r.foundation_time), "s");
  s.set("final_stage", std::string(stage_name(r.final_stage)));
  s.set("final_bottom_width", r.final_bottom_width, "m");
  s.set("final_top_width", r.final_top_width, "m");
  s.set("final_depth", r.final_depth, "m");
  s.set("final_invert", r.final_invert, "m");
  s.set("final_level", r.final_level, "m");
  s.set("eroded_volume", r.eroded_volume, "m^3");
  s.set("volume_above_invert_at_failure", r.volume_above_invert_at_failure, "m^3");
  s.set("head_above_invert_at_failure", r.head_above_invert_at_failure, "m");
  s.set("inflow_volume", r.inflow_volume, "m^3");
  s.set("outflow_volume", r.outflow_volume, "m^3");
  s.set("storage_change", r.storage_change, "m^3");
  s.set("mass_balance_error", r.mass_balance_error, "m^3");
  s.set("steps", static_cast<double>(r.steps));
  s.set("rejected_steps", static_cast<double>(r.rejected_steps));
  s.set("evaluations", static_cast<double>(r.evaluations));
  return s;
}

int run_breach(const mpi::Comm& comm, const config::Config& cfg, const RunOptions& options, Logger& log) {
  if (comm.size() != 1)
    throw InputError(
        fmt::format("breach runs one scene on one process, not {}; to run many scenes at once use "
                    "`study` (in-process, MPI workers or a Slurm array)",
                    comm.size()));
  PhaseTimers timers;
  RunRecord record(comm, "breach", options.argv);
  record.extra()["scene"] = cfg.source_name();
  const Scene scene = Scene::read(cfg.root());
  const bool plot = cfg.root().section_or_empty("output").get<bool>("plot", true);
  cfg.finish();
  const auto out = io::prepare_output_dir(comm, options.out);
  cfg.write_effective(out / "effective_config.yaml");

  log.info("dam {} m high, crest {} m long; soil kd = {:.4g} cm^3/(N s), tau_c = {:.4g} Pa; {} to {} h, {} steps",
           scene.dam.height, scene.dam.crest_length, scene.soil.kd * 1e6, scene.soil.tau_c, scene.time.start / 3600.0,
           scene.time.end / 3600.0,
           scene.time.adaptive ? fmt::format("adaptive (tolerance {:g})", scene.time.tolerance)
                               : fmt::format("fixed {} s", scene.time.fixed_step));
  io::CsvSeries csv(out / "hydrograph.csv", kColumns);
  std::optional<Stage> last;
  Result result;
  {
    ScopedPhase phase(timers, "integrate");
    result = simulate(scene, [&](const Sample& s) {
      csv.append(hydrograph_row(s));
      if (s.stage != last) log.info("t = {:.3f} h: {}", s.time / 3600.0, stage_name(s.stage));  // as sampled
      last = s.stage;
    });
  }
  log.info("peak outflow {:.4g} m^3/s at {:.3f} h; {}; final breach {:.3g} m deep, {:.3g} m wide at the bottom",
           result.peak_outflow, result.time_to_peak / 3600.0,
           result.initiation_time ? fmt::format("breach initiated at {:.3f} h", *result.initiation_time / 3600.0)
                                  : std::string("no breach"),
           result.final_depth, result.final_bottom_width);
  if (result.rising_at_end)
    log.warn(
        "the outflow is still rising at the end of the run ({:.3f} h): the event has not finished and its "
        "peak is not known; extend time.end",
        scene.time.end / 3600.0);
  log.info("{} steps ({} rejected), {} evaluations; mass balance error {:.3g} m^3 of {:.4g} m^3 inflow", result.steps,
           result.rejected_steps, result.evaluations, result.mass_balance_error, result.inflow_volume);
  make_summary(result).write(out / "summary.json");
  if (plot) {
    ScopedPhase phase(timers, "plot");
    const std::string cmd = plot_command(out);
    if (std::system(cmd.c_str()) != 0) log.warn("the plot failed (command: {}); the results are complete", cmd);
  }
  record.write(out / "run.json", timers, "completed");
  return 0;
}

}  // namespace suite::breach
