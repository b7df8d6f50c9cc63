// breach: the fast embankment overtopping-breach model (docs/methods/breach.md).
//   breach [scene.yaml] [key.path=value ...] [--out DIR]
//   breach [scene.yaml] [key.path=value ...] --dakota params.in results.out [--out DIR]   (Dakota
//   driver; with --out each evaluation also writes its outputs there)
// Without a scene it runs the embedded default (examples/embankment_overtopping.yaml).
#include "core/cli/solver_main.hpp"
#include "solvers/breach/run/dakota_driver.hpp"
#include "solvers/breach/run/run_breach.hpp"

namespace suite::embedded {
extern const char* const breach_default_yaml;
}

int main(int argc, char** argv) {
  const suite::cli::SolverProgram program{
      {"breach", "Embankment overtopping breach: reservoir routing, surface erosion, headcut advance, breach growth",
       false, "breach-out", true},
      suite::embedded::breach_default_yaml,
      "embankment_overtopping.yaml"};
  return suite::cli::solver_main(argc, argv, program, [](const suite::cli::SolverRun& r) {
    const auto& cl = r.command_line;
    // As a Dakota driver the model runs in-process per evaluation, without an output folder,
    // unless --out asks for the evaluation's outputs.
    if (cl.dakota && cl.out_given)
      return r.dakota_driver([&](const suite::config::Config& scene) {
        return suite::breach::run_breach(r.world, scene, {cl.out, cl.argv}, r.log);
      });
    if (cl.dakota)
      return suite::breach::run_dakota_driver(cl.scene, suite::embedded::breach_default_yaml, cl.overrides,
                                              cl.dakota->first, cl.dakota->second);
    return suite::breach::run_breach(r.world, r.scene(), {cl.out, cl.argv}, r.log);
  });
}
