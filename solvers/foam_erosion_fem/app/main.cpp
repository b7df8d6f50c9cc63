// foam-erosion: OpenFOAM overtopping flow coupled step-wise to an FEM erosion model of the dam
// surface (docs/methods/foam_erosion_fem.md).
//   foam-erosion [scene.yaml] [key.path=value ...] [--out DIR]        build, run, couple, write
//   foam-erosion case [scene.yaml] [key.path=value ...] [--out DIR]   only write the case
//   foam-erosion [scene.yaml] ... --out DIR --restart latest           go on from DIR/state.json
//   foam-erosion [scene.yaml] ... --dakota params.in results.out       a Dakota analysis driver
//     (variables are scene keys, responses keys of summary.json)
// Without a scene it runs the embedded default (scenes/lab_embankment.yaml).
#include <cstring>
#include <string>
#include <vector>

#include "core/cli/solver_main.hpp"
#include "core/errors.hpp"
#include "solvers/foam_erosion_fem/run/run_foam_erosion.hpp"

namespace suite::embedded {
extern const char* const foam_erosion_default_yaml;
}

int main(int argc, char** argv) {
  // "case" as the first argument: write the case only. The rest stays a null-terminated array
  // (MPI_Init reads it as one).
  std::vector<char*> args(argv, argv + argc + 1);
  const bool case_only = argc > 1 && std::strcmp(argv[1], "case") == 0;
  if (case_only) args.erase(args.begin() + 1);
  const suite::cli::SolverProgram program{
      {"foam-erosion",
       "OpenFOAM (interFoam) overtopping flow coupled to an FEM erosion model of the dam surface.\n"
       "'foam-erosion case [scene] ...' only writes the OpenFOAM case (meshed) for inspection",
       false, "foam-erosion-out", true},
      suite::embedded::foam_erosion_default_yaml,
      "lab_embankment.yaml"};
  return suite::cli::solver_main(
      static_cast<int>(args.size()) - 1, args.data(), program,
      [&](const suite::cli::SolverRun& r) {
        if (r.world.size() > 1)
          throw suite::InputError("foam-erosion starts OpenFOAM's own MPI runs (run.ranks); start it on one rank, "
                                  "not under mpiexec -n " + std::to_string(r.world.size()));
        const auto& cl = r.command_line;
        if (cl.dakota)
          return r.dakota_driver([&](const suite::config::Config& scene) {
            return suite::foam_erosion::run_foam_erosion(scene, {cl.out, false, false, cl.argv}, r.log);
          });
        return suite::foam_erosion::run_foam_erosion(r.scene(), {cl.out, case_only, cl.restart.has_value(), cl.argv},
                                                     r.log);
      });
}
