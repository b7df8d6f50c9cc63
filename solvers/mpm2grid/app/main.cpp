// mpm2grid: two-grid soil-water Material Point Method (docs/methods/mpm2grid.md, issue 3).
//   mpm2grid [scene.yaml] [key.path=value ...] [--out DIR]
//   mpm2grid [scene.yaml] [key.path=value ...] [--out DIR] --dakota params.in results.out
//     (a Dakota analysis driver: variables are scene keys, responses keys of summary.json)
// Without a scene it runs the embedded default (scenes/water_column_collapse.yaml).
#include <cstdio>

#include "core/cli/command_line.hpp"
#include "core/config/config.hpp"
#include "core/dakota/analysis_driver.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "solvers/mpm2grid/io/run_mpm.hpp"

namespace suite::embedded {
extern const char* const mpm2grid_default_yaml;
}

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse(
        {"mpm2grid", "Two-grid soil-water Material Point Method (APIC, Drucker-Prager soil, implicit drag)", false,
         "mpm2grid-out", true},
        argc, argv);
    if (!parsed.command_line) {
      if (world.is_root()) std::fprintf(parsed.exit_code ? stderr : stdout, "%s\n", parsed.message.c_str());
      return parsed.exit_code;
    }
    const auto& cl = *parsed.command_line;
    suite::Logger log(world, "mpm2grid", {suite::parse_log_level(cl.log_level), cl.log_all_ranks, nullptr});
    const auto scene_with = [&](const std::vector<std::string>& overrides) {
      return cl.scene ? suite::config::Config::from_file(*cl.scene, overrides)
                      : suite::config::Config::from_string(suite::embedded::mpm2grid_default_yaml,
                                                           "<embedded water_column_collapse.yaml>", overrides);
    };
    if (cl.dakota)
      return suite::dakota::run_analysis_driver(
          world, "mpm2grid", cl.overrides, cl.dakota->first, cl.dakota->second, [&](const auto& overrides) {
            if (world.is_root()) std::filesystem::remove(cl.out / "summary.json");  // not an earlier run's
            world.barrier();
            if (suite::mpm2grid::run_mpm(world, scene_with(overrides), {cl.out, std::nullopt, cl.argv}, log) != 0)
              throw suite::dakota::EvaluationFailed("the run did not finish (see " + (cl.out / "log.txt").string() + ")");
            return suite::dakota::read_summary(cl.out);
          });
    return suite::mpm2grid::run_mpm(world, scene_with(cl.overrides), {cl.out, cl.restart, cl.argv}, log);
  });
}
