#include "solvers/foam_erosion_fem/run/run_foam_erosion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/checkpoint/scene_match.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/output_dir.hpp"
#include "core/mpi/comm.hpp"
#include "core/run/phase_timers.hpp"
#include "core/run/run_record.hpp"
#include "core/run/signals.hpp"
#include "solvers/foam_erosion_fem/coupling/discharge.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"
#include "solvers/foam_erosion_fem/run/breach_comparison.hpp"
#include "solvers/foam_erosion_fem/run/coupled_loop.hpp"
#include "solvers/foam_erosion_fem/run/prepare_case.hpp"

namespace suite::foam_erosion {

namespace {

// discharge.csv, and the peak discharge and water volume of each section (over the whole crest
// length). interFoam records each step's discharge at the step's end, so a value stands for the
// step before it.
void write_discharge_outputs(const std::filesystem::path& case_dir, const std::filesystem::path& out, double scale,
                             Summary& summary) {
  const std::vector<std::string> sections{"inlet", "crest", "toe", "outlet"};
  std::vector<DischargeSeries> series;
  for (const auto& name : sections) series.push_back(read_discharge(case_dir, name));
  write_discharge_csv(out / "discharge.csv", sections, series, scale);
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const auto& d = series[k];
    double peak = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < d.water.size(); ++i) {
      peak = std::max(peak, std::abs(d.water[i]) * scale);
      if (i > 0) volume += (d.time[i] - d.time[i - 1]) * d.water[i] * scale;
    }
    summary.set("peak_" + sections[k] + "_discharge", peak, "m^3/s");
    summary.set(sections[k] + "_water_volume", std::abs(volume), "m^3");  // the inlet's flux is negative (inward)
  }
}

// The scene a coupled run was started with, kept beside state.json for its restarts.
constexpr const char* kSceneKeysFile = "scene_keys.txt";

// A restart continues the run in `out` only with the scene it was started with; a later
// time.end extends it. InputError naming every key that differs otherwise.
void check_restart_scene(const FoamScene& scene, const checkpoint::SceneRecord& now, const std::filesystem::path& out,
                         const LoopState& state) {
  const auto file = out / kSceneKeysFile;
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("{}: missing, so the scene of the run in {} is unknown; start again without "
                                 "--restart",
                                 file.string(), out.string()));
  std::stringstream text;
  text << in.rdbuf();
  const auto where = fmt::format("the coupled-loop state in {}", out.string());
  const auto saved = checkpoint::SceneRecord::from_text(text.str(), file.string());
  saved.require_same(now, {"time.end"}, where);
  checkpoint::require_later_end(scene.time.end, state.time, where);
  if (scene.inflow.kind() == Hydrograph::Kind::sine && saved.keys().at("time.end") != now.keys().at("time.end"))
    throw InputError(fmt::format("time.end: the case's inlet table samples the sine inflow only up to the first run's "
                                 "end ({}), so {} cannot be extended; start a new run with the longer time.end",
                                 saved.keys().at("time.end"), where));
}

}  // namespace

int run_foam_erosion(const config::Config& cfg, const RunOptions& o, Logger& log) {
  const auto scene = FoamScene::read(cfg.root());
  cfg.finish();
  const checkpoint::SceneRecord scene_keys(cfg);
  const mpi::Comm self(MPI_COMM_SELF);
  const auto out = io::prepare_output_dir(self, o.out);
  cfg.write_effective(out / "effective_config.yaml");
  log.add_file(out / "log.txt");
  suite::RunRecord record(self, "foam-erosion", o.argv);
  PhaseTimers timers;
  // SIGTERM/SIGINT (Slurm's time limit, scancel, Ctrl-C) stop interFoam and end the run with the
  // outputs of the steps done; state.json is written after every step, so SIGUSR1 has nothing to add.
  SignalWatcher signals(out);
  bool stop = false;
  std::string stop_reason;  // "signal 15", or the stop file's request
  RunnerOptions runner_options;
  runner_options.stop_requested = [&] {
    if (stop) return true;
    const auto request = signals.poll(self);
    // A request file sends no signal (last_signal() stays 0): name the request instead.
    const auto reason = [&] {
      return signals.last_signal() ? fmt::format("signal {}", signals.last_signal()) : std::string(describe(request));
    };
    if (request == SignalRequest::checkpoint)
      log.info("{}: nothing to save, state.json is written after every coupling step", reason());
    stop = request == SignalRequest::checkpoint_and_stop;
    if (stop) stop_reason = reason();
    return stop;
  };
  FoamRunner runner(out / "case", out / "logs", runner_options);
  Summary summary;
  std::string status = o.case_only ? "case written" : "finished";
  int exit_code = 0;
  const double slab_scale = scene.dam.crest_length / SectionLayout::initial(scene).thickness;
  try {
    PreparedCase prepared;
    std::optional<LoopState> resume;
    if (o.restart) {
      resume = LoopState::read(out / "state.json");
      check_restart_scene(scene, scene_keys, out, *resume);
      prepared = resume_case(scene, runner.case_dir(), *resume);
      log.info("restarting from {}: step {} at t = {} s, {} re-meshes so far", (out / "state.json").string(),
               resume->step, resume->time, resume->remeshes);
    } else {
      for (const char* stale : {"case", "cases", "state.json"}) std::filesystem::remove_all(out / stale);
      io::write_file_atomic(out / kSceneKeysFile, scene_keys.text());
      ScopedPhase phase(timers, "case");
      prepared = prepare_case(scene, runner, scene.time.end);
    }
    log.info("case {}: {} flow cells ({} in the background, the dam's cut out), {} staircase dam faces, {} FEM "
             "dam elements; {}",
             runner.case_dir().string(), prepared.mesh.cells, prepared.mesh.background_cells, prepared.mesh.dam_faces,
             prepared.layout.dam_nodes.size() - 1, o.restart ? "as the interrupted run left it" : "meshed and checked");
    summary.set("cells", static_cast<double>(prepared.mesh.cells));
    summary.set("dam_faces", static_cast<double>(prepared.mesh.dam_faces));
    summary.set("dam_elements", static_cast<double>(prepared.layout.dam_nodes.size() - 1));
    if (!o.case_only) {
      const auto result = run_coupled(scene, runner, prepared, out, log, timers, resume ? &*resume : nullptr);
      summary.set("flow_steps", static_cast<double>(result.flow_steps));
      summary.set("max_courant", result.max_courant);
      summary.set("erosion_steps", static_cast<double>(result.erosion_steps));
      summary.set("remeshes", static_cast<double>(result.remeshes));
      summary.set("eroded_area", result.eroded_area, "m^2/m");
      summary.set("eroded_volume", result.eroded_area * scene.dam.crest_length, "m^3");
      summary.set("final_crest_height", result.final_crest - scene.dam.foundation, "m");
      if (!result.failure.empty()) {
        log.error("{}", result.failure);
        log.warn("the {} finished coupling step(s) are kept: erosion.csv, profiles.csv, state.json and summary.json in "
                 "{}",
                 result.erosion_steps, out.string());
        summary.set("failure", result.failure.substr(0, result.failure.find('\n')));  // its first line
        status = "failed";
        exit_code = 3;
      }
    }
  } catch (const FoamRunStopped& e) {
    const auto saved = out / "state.json";
    log.warn("stopped on {} ({}); {}; continue with --restart latest", stop_reason, e.what(),
             std::filesystem::exists(saved)
                 ? fmt::format("{} holds coupling step {}", saved.string(), LoopState::read(saved).step)
                 : std::string("no coupling step was finished"));
    status = "stopped";
  } catch (const FoamRunError& e) {
    // A failed OpenFOAM program is a result of the run, not a crash of this one: say which and
    // where its log is, keep the case and what was written, exit 3.
    log.error("{}", e.what());
    status = "failed";
    exit_code = 3;
  }
  if (!o.case_only) {
    try {
      write_discharge_outputs(runner.case_dir(), out, slab_scale, summary);
    } catch (const FoamReadError& e) {
      log.warn("no discharge record written: {}", e.what());
    }
    write_breach_comparison(scene, out, summary, log);
  }
  summary.set("status", status);
  summary.write(out / "summary.json");
  record.write(out / "run.json", timers,
               exit_code != 0 ? "failed" : status == "stopped" ? "stopped: " + stop_reason
                                                               : "finished");
  return exit_code;
}

}  // namespace suite::foam_erosion
