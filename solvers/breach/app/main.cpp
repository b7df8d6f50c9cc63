// breach: the fast embankment overtopping-breach model (docs/methods/breach.md).
//   breach [scene.yaml] [key.path=value ...] [--out DIR]
//   breach [scene.yaml] [key.path=value ...] --dakota params.in results.out   (Dakota driver)
// Without a scene it runs the embedded default (examples/embankment_overtopping.yaml).
#include <cstdio>

#include "core/cli/command_line.hpp"
#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "solvers/breach/io/dakota_driver.hpp"
#include "solvers/breach/io/run_breach.hpp"

namespace suite::embedded {
extern const char* const breach_default_yaml;
}

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse(
        {"breach", "Embankment overtopping breach: reservoir routing, surface erosion, headcut advance, breach growth",
         false, "breach-out", true},
        argc, argv);
    if (!parsed.command_line) {
      if (world.is_root()) std::fprintf(parsed.exit_code ? stderr : stdout, "%s\n", parsed.message.c_str());
      return parsed.exit_code;
    }
    const auto& cl = *parsed.command_line;
    if (cl.dakota)
      return suite::breach::run_dakota_driver(cl.scene, suite::embedded::breach_default_yaml, cl.overrides,
                                              cl.dakota->first, cl.dakota->second);
    suite::Logger log(world, "breach", {suite::parse_log_level(cl.log_level), cl.log_all_ranks, nullptr});
    const auto scene = cl.scene
                           ? suite::config::Config::from_file(*cl.scene, cl.overrides)
                           : suite::config::Config::from_string(suite::embedded::breach_default_yaml,
                                                                "<embedded embankment_overtopping.yaml>", cl.overrides);
    return suite::breach::run_breach(world, scene, {cl.out, cl.argv}, log);
  });
}
