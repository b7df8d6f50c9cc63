#include "solvers/foam_erosion_fem/io/run_foam_erosion.hpp"

#include <fmt/format.h>

#include "core/io/output_dir.hpp"
#include "core/mpi/comm.hpp"
#include "core/run/phase_timers.hpp"
#include "core/run/run_record.hpp"
#include "solvers/foam_erosion_fem/io/prepare_case.hpp"

namespace suite::foam_erosion {

int run_foam_erosion(const config::Config& cfg, const RunOptions& o, Logger& log) {
  const auto scene = FoamScene::read(cfg.root());
  cfg.finish();
  const mpi::Comm self(MPI_COMM_SELF);
  const auto out = io::prepare_output_dir(self, o.out);
  cfg.write_effective(out / "effective_config.yaml");
  log.add_file(out / "log.txt");
  suite::RunRecord record(self, "foam-erosion", o.argv);
  PhaseTimers timers;
  FoamRunner runner(out / "case", out / "logs");
  Summary summary;
  try {
    PreparedCase prepared;
    {
      ScopedPhase phase(timers, "case");
      prepared = prepare_case(scene, runner, scene.time.end);
    }
    log.info("case {}: {} cells, {} dam elements; meshed and checked", runner.case_dir().string(),
             prepared.layout.cells(), prepared.layout.dam_nodes.size() - 1);
    summary.set("cells", static_cast<double>(prepared.layout.cells()));
    summary.set("dam_elements", static_cast<double>(prepared.layout.dam_nodes.size() - 1));
    if (!o.case_only) {
      ScopedPhase phase(timers, "flow");
      const auto flow = runner.run("interFoam", {}, scene.run.ranks);
      log.info("interFoam: {} steps in {:.1f} s, max Courant {}", flow.time_steps, flow.wall_seconds,
               flow.max_courant);
      summary.set("flow_steps", static_cast<double>(flow.time_steps));
      summary.set("max_courant", flow.max_courant);
    }
  } catch (const FoamRunError& e) {
    // A failed OpenFOAM program is a result of the run, not a crash of this one: say which and
    // where its log is, keep the case and what was written, exit 3.
    log.error("{}", e.what());
    summary.set("status", "failed");
    summary.write(out / "summary.json");
    record.write(out / "run.json", timers, "failed");
    return 3;
  }
  summary.set("status", o.case_only ? "case written" : "finished");
  summary.write(out / "summary.json");
  record.write(out / "run.json", timers, "finished");
  return 0;
}

}  // namespace suite::foam_erosion
