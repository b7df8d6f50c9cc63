#pragma once
// The coupled loop (spec steps 5-7): interFoam runs one coupling interval at a time; after each
// the bed shear on the dam is mapped onto the FEM curve, the curve erodes by the excess-stress
// law over that interval (times the morphological factor), and when the eroded curve changes
// the flow cells the case is re-meshed and its fields mapped (coupling/remesh.hpp). A scene with
// kd = 0 runs the flow in one go.
//
// A failed OpenFOAM program (FoamRunError), a result that cannot be read (FoamReadError) or a
// curve the erosion step cannot keep valid ends the loop with `failure` set, naming the step;
// FoamRunStopped (a stop request) propagates. Either way erosion.csv, profiles.csv, state.json
// and the result hold every step finished.
#include <filesystem>
#include <string>

#include "core/log/logger.hpp"
#include "core/run/phase_timers.hpp"
#include "solvers/foam_erosion_fem/coupling/loop_state.hpp"
#include "solvers/foam_erosion_fem/run/prepare_case.hpp"

namespace suite::foam_erosion {

struct CoupledRunResult {
  int erosion_steps = 0;
  int remeshes = 0;
  double eroded_area = 0.0;  // m^2 per metre of crest
  double final_crest = 0.0;  // highest dam node after the last step, m (level)
  long long flow_steps = 0;
  double max_courant = 0.0;
  std::string failure;  // empty when the loop reached time.end
};

// `resume`: go on from a restart state (coupling/loop_state.hpp) instead of t = 0; `prepared`
// then describes the case as it is on disk (see resume_case). state.json is written after
// every step either way.
CoupledRunResult run_coupled(const FoamScene& scene, FoamRunner& runner, PreparedCase& prepared,
                             const std::filesystem::path& out, Logger& log, PhaseTimers& timers,
                             const LoopState* resume = nullptr);

// The case of an output folder made ready to go on from `state`: the time directories after
// state.time and the records of the interrupted segment removed; the layout, background and
// flow cells rebuilt from the state and constant/background.
PreparedCase resume_case(const FoamScene& scene, const std::filesystem::path& case_dir, const LoopState& state);

}  // namespace suite::foam_erosion
