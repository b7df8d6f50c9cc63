// suite-demo: the suite's main job on its embedded default scene (README, quick start).
// Until the MPM and OpenFOAM solvers land it runs the Ritter dam-break reference; each solver
// issue adds its demo here.
#include <cstdio>

#include "core/cli/command_line.hpp"
#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "demo/ritter/dam_break_run.hpp"

namespace suite::embedded {
extern const char* const ritter_dam_break_yaml;
}

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse(
        {"suite-demo", "Suite demo: the default dam-break scene (Ritter's analytic solution) with the suite's outputs",
         false, "suite-demo-out"},
        argc, argv);
    if (!parsed.command_line) {
      if (world.is_root()) std::fprintf(parsed.exit_code ? stderr : stdout, "%s\n", parsed.message.c_str());
      return parsed.exit_code;
    }
    const auto& cl = *parsed.command_line;
    suite::Logger log(world, "suite-demo", {suite::parse_log_level(cl.log_level), cl.log_all_ranks, nullptr});
    const auto scene = cl.scene ? suite::config::Config::from_file(*cl.scene, cl.overrides)
                                : suite::config::Config::from_string(suite::embedded::ritter_dam_break_yaml,
                                                                     "<embedded ritter_dam_break.yaml>", cl.overrides);
    return suite::demo::run_dam_break(world, scene, {cl.out, cl.restart, cl.argv}, log);
  });
}
