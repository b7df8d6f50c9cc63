#pragma once
// One breach run, as a library call (studies call it thousands of times in one process; it
// allocates nothing per step and touches no files) and as the engine of the `breach` executable.
//
// Time integration: Dormand-Prince 5(4) with the standard error-per-step control (Hairer,
// Norsett & Wanner, sec. II.4) on all state components, each measured against
// tolerance x (|y| + its typical magnitude), stepping exactly onto the hydrograph's kinks and,
// when an observer is given, onto output times. The ends of the stages and the breach reaching
// the crest length are located inside the step (Illinois regula falsi on the step size) so the
// switch happens at the right time, not at the next step. Results change by less than the
// tolerance's order when the tolerance is tightened (tests/breach). A fixed-step mode (same
// scheme, no error control) exists for the speed-versus-accuracy chart.
#include <functional>
#include <optional>
#include <string>

#include "solvers/breach/model/breach_state.hpp"
#include "solvers/breach/model/scene.hpp"

namespace suite::breach {

// One row of the time series.
struct Sample {
  double time = 0.0;
  Stage stage = Stage::surface_erosion;
  Flows flows;
  double stress = 0.0;  // Pa, the active stage's erosion stress
  double face_erosion = 0.0, headcut_position = 0.0, headcut_height = 0.0;
  double invert = 0.0, bottom_width = 0.0, top_width = 0.0, eroded_volume = 0.0;
};
using Observer = std::function<void(const Sample&)>;

struct Result {
  double peak_outflow = 0.0;                                                       // m^3/s, breach + crest + spillway
  double time_to_peak = 0.0;                                                       // s from time.start
  double peak_breach_outflow = 0.0;                                                // m^3/s, through the breach alone
  // The outflow was still rising when the run ended: the peak above is the run's, not the
  // event's, which had not finished; a later time.end finds the event's.
  bool rising_at_end = false;
  std::optional<double> headcut_formation_time, initiation_time, foundation_time;  // s from start
  bool failed() const { return initiation_time.has_value(); }
  Stage final_stage = Stage::surface_erosion;
  double final_level = 0.0, final_invert = 0.0, final_depth = 0.0;  // m; depth = crest - invert
  double final_bottom_width = 0.0, final_top_width = 0.0, eroded_volume = 0.0;
  // At breach initiation, above the final invert (Froehlich's Vw and hw); 0 if no breach.
  double volume_above_invert_at_failure = 0.0, head_above_invert_at_failure = 0.0;
  // Reservoir balance over the run (m^3): inflow - outflow - storage change = mass_balance_error.
  double inflow_volume = 0.0, outflow_volume = 0.0, storage_change = 0.0, mass_balance_error = 0.0;
  long steps = 0, rejected_steps = 0, evaluations = 0;
};

// Runs the scene from time.start to time.end. `observe`, if given, receives the initial state,
// a row every scene.output_interval and the final state. Throws std::runtime_error naming time
// and step if the solution turns non-finite or the step size collapses.
Result simulate(const Scene& scene, const Observer& observe = {});

const char* stage_name(Stage stage);

}  // namespace suite::breach
