// suite-demo: the Ritter dam-break reference through the suite's whole output path (README,
// quick start): HDF5 + XDMF fields, CSV series with units, run.json, summary.json, checkpoints.
#include "core/cli/solver_main.hpp"
#include "demo/ritter/dam_break_run.hpp"

namespace suite::embedded {
extern const char* const ritter_dam_break_yaml;
}

int main(int argc, char** argv) {
  const suite::cli::SolverProgram program{
      {"suite-demo", "Suite demo: the default dam-break scene (Ritter's analytic solution) with the suite's outputs",
       false, "suite-demo-out"},
      suite::embedded::ritter_dam_break_yaml,
      "ritter_dam_break.yaml"};
  return suite::cli::solver_main(
      argc, argv, program,
      [](const suite::cli::SolverRun& r) {
        const auto& cl = r.command_line;
        return suite::demo::run_dam_break(r.world, r.scene(), {cl.out, cl.restart, cl.argv}, r.log);
      });
}
