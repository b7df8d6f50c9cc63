#include "core/cli/solver_main.hpp"

#include <cstdio>

#include "core/dakota/analysis_driver.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"

namespace suite::cli {

config::Config SolverRun::scene(const std::vector<std::string>& overrides) const {
  if (command_line.scene) return config::Config::from_file(*command_line.scene, overrides);
  return config::Config::from_string(program.default_scene, "<embedded " + program.default_scene_file + ">", overrides);
}

int SolverRun::dakota_driver(const std::function<int(const config::Config& scene)>& run_once) const {
  const auto& cl = command_line;
  return dakota::run_analysis_driver(
      world, program.spec.program, cl.overrides, cl.dakota->first, cl.dakota->second,
      [&](const std::vector<std::string>& overrides) {
        if (world.is_root()) std::filesystem::remove(cl.out / "summary.json");  // not an earlier run's
        world.barrier();
        const int rc = run_once(scene(overrides));
        const auto log_file = (cl.out / "log.txt").string();
        if (rc != 0) throw dakota::EvaluationFailed("the run did not finish (see " + log_file + ")");
        auto summary = dakota::read_summary(cl.out);
        if (summary.contains("status") && summary.value("status", "") != "finished")
          throw dakota::EvaluationFailed("the run ended '" + summary.value("status", std::string("?")) + "' (see " +
                                         log_file + ")");
        return summary;
      });
}

int solver_main(int argc, char** argv, const SolverProgram& program, const std::function<int(const SolverRun&)>& run) {
  mpi::Environment env(argc, argv);
  const mpi::Comm world(MPI_COMM_WORLD);
  return guarded_main(world, [&] {
    const auto parsed = parse(program.spec, argc, argv);
    if (!parsed.command_line) {
      if (world.is_root()) std::fprintf(parsed.exit_code ? stderr : stdout, "%s\n", parsed.message.c_str());
      return parsed.exit_code;
    }
    const auto& cl = *parsed.command_line;
    Logger log(world, program.spec.program, {parse_log_level(cl.log_level), cl.log_all_ranks, nullptr});
    return run({world, cl, log, program});
  });
}

}  // namespace suite::cli
