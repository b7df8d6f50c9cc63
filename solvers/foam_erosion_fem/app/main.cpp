// foam-erosion: OpenFOAM overtopping flow coupled step-wise to an FEM erosion model of the dam
// surface (docs/methods/foam_erosion_fem.md, issue 7).
//   foam-erosion [scene.yaml] [key.path=value ...] [--out DIR]        build, run, couple, write
//   foam-erosion case [scene.yaml] [key.path=value ...] [--out DIR]   only write the case
//   foam-erosion [scene.yaml] ... --out DIR --restart latest           go on from DIR/state.json
//   foam-erosion [scene.yaml] ... --dakota params.in results.out       a Dakota analysis driver
//     (variables are scene keys, responses keys of summary.json)
// Without a scene it runs the embedded default (scenes/lab_embankment.yaml).
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/cli/command_line.hpp"
#include "core/config/config.hpp"
#include "core/dakota/analysis_driver.hpp"
#include "core/errors.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "solvers/foam_erosion_fem/io/run_foam_erosion.hpp"

namespace suite::embedded {
extern const char* const foam_erosion_default_yaml;
}

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  // "case" as the first argument: write the case only.
  std::vector<char*> args(argv, argv + argc);
  const bool case_only = argc > 1 && std::strcmp(argv[1], "case") == 0;
  if (case_only) args.erase(args.begin() + 1);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse(
        {"foam-erosion",
         "OpenFOAM (interFoam) overtopping flow coupled to an FEM erosion model of the dam surface.\n"
         "'foam-erosion case [scene] ...' only writes the OpenFOAM case (meshed) for inspection",
         false, "foam-erosion-out", true},
        static_cast<int>(args.size()), args.data());
    if (!parsed.command_line) {
      if (world.is_root()) std::fprintf(parsed.exit_code ? stderr : stdout, "%s\n", parsed.message.c_str());
      return parsed.exit_code;
    }
    const auto& cl = *parsed.command_line;
    suite::Logger log(world, "foam-erosion", {suite::parse_log_level(cl.log_level), cl.log_all_ranks, nullptr});
    if (world.size() > 1)
      throw suite::InputError("foam-erosion starts OpenFOAM's own MPI runs (run.ranks); start it on one rank, "
                              "not under mpiexec -n " + std::to_string(world.size()));
    const auto scene_with = [&](const std::vector<std::string>& overrides) {
      return cl.scene ? suite::config::Config::from_file(*cl.scene, overrides)
                      : suite::config::Config::from_string(suite::embedded::foam_erosion_default_yaml,
                                                           "<embedded lab_embankment.yaml>", overrides);
    };
    if (cl.dakota)
      return suite::dakota::run_analysis_driver(
          world, "foam-erosion", cl.overrides, cl.dakota->first, cl.dakota->second, [&](const auto& overrides) {
            std::filesystem::remove(cl.out / "summary.json");  // not an earlier run's
            const int rc = suite::foam_erosion::run_foam_erosion(scene_with(overrides), {cl.out, false, false, cl.argv}, log);
            auto summary = suite::dakota::read_summary(cl.out);
            if (rc != 0 || summary.value("status", "") != "finished")
              throw suite::dakota::EvaluationFailed("the run ended '" + summary.value("status", std::string("?")) +
                                                    "' (see " + (cl.out / "log.txt").string() + ")");
            return summary;
          });
    return suite::foam_erosion::run_foam_erosion(scene_with(cl.overrides), {cl.out, case_only, cl.restart.has_value(), cl.argv}, log);
  });
}
