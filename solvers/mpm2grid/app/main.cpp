// mpm2grid: two-grid soil-water Material Point Method (docs/methods/mpm2grid.md).
//   mpm2grid [scene.yaml] [key.path=value ...] [--out DIR]
//   mpm2grid [scene.yaml] [key.path=value ...] [--out DIR] --dakota params.in results.out
//     (a Dakota analysis driver: variables are scene keys, responses keys of summary.json)
// Without a scene it runs the embedded default (scenes/water_column_collapse.yaml).
#include "core/cli/solver_main.hpp"
#include "solvers/mpm2grid/run/run_mpm.hpp"

namespace suite::embedded {
extern const char* const mpm2grid_default_yaml;
}

int main(int argc, char** argv) {
  const suite::cli::SolverProgram program{
      {"mpm2grid", "Two-grid soil-water Material Point Method (APIC, Drucker-Prager soil, implicit drag)", false,
       "mpm2grid-out", true},
      suite::embedded::mpm2grid_default_yaml,
      "water_column_collapse.yaml"};
  return suite::cli::solver_main(argc, argv, program, [](const suite::cli::SolverRun& r) {
    const auto& cl = r.command_line;
    if (cl.dakota)
      return r.dakota_driver([&](const suite::config::Config& scene) {
        return suite::mpm2grid::run_mpm(r.world, scene, {cl.out, std::nullopt, cl.argv}, r.log);
      });
    return suite::mpm2grid::run_mpm(r.world, r.scene(), {cl.out, cl.restart, cl.argv}, r.log);
  });
}
