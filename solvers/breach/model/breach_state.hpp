#pragma once
// The breach model's state, its stages, and the right-hand side the integrator advances
// (docs/methods/breach.md; the stage structure of WinDAM C, Temple et al. 2005, Hanson et al. 2005):
//
//   stage 0  internal erosion (only when the scene has `internal_erosion`, instead of 1 and 2):
//            a pipe through the embankment grows at 2 kd (tau - tau_c) until its roof collapses;
//            that is breach initiation, and the breach forms from the pipe's invert.
//   stage 1  surface erosion: concentrated flow of width b0 down the downstream face at Manning
//            normal depth erodes the face at kd (tau_e - tau_c); when the eroded depth reaches
//            the formation depth a headcut forms at the toe.
//   stage 2  headcut advance: the headcut (height = formation depth + embankment surface above
//            the foundation at its position) moves upstream at the jet-scour / mass-failure rate
//            of headcut.hpp; the control section stays on the intact crest. Breach initiation is
//            the moment it reaches the upstream edge of the crest.
//   stage 3  breach formation: the control (a trapezoid of bottom width b, side slopes s) lowers
//            at kd (tau_e - tau_c) with tau_e at the critical section, and both walls retreat at
//            the bed rate (db/dt = 2 x rate) up to the crest length.
//   stage 4  breach widening: the invert has reached the foundation; only widening goes on.
//
// Reservoir continuity (level pool): dV/dt = Q_in(t) - Q_breach - Q_crest - Q_spillway. The
// state holds W = V - (inflow volume since the start), whose derivative is minus the outflow:
// the inflow enters through the hydrograph's exact integral, so inflow - outflow - storage change
// closes to round-off whatever the step.
#include <array>

#include "solvers/breach/model/scene.hpp"

namespace suite::breach {

enum class Stage {
  internal_erosion = 0,
  surface_erosion = 1,
  headcut_advance = 2,
  breach_formation = 3,
  breach_widening = 4
};

// Components of the state vector.
enum Component : std::size_t {
  kStorageLessInflow,  // W (m^3)
  kBreachVolume,       // outflow volume through the breach / notch so far (m^3)
  kCrestVolume,        // over the rest of the crest (m^3)
  kSpillwayVolume,     // through the spillway (m^3)
  kFaceErosion,        // eroded depth on the face, stage 1 (m)
  kHeadcutPosition,    // headcut distance from the downstream toe, stage 2 (m)
  kInvert,             // breach invert level (m); the pipe's invert in stage 0
  kBottomWidth,        // breach bottom width (m); the pipe's diameter in stage 0
  kComponents
};
using StateVector = std::array<double, kComponents>;

// Outflows and reservoir condition at one state.
struct Flows {
  double level = 0.0, storage = 0.0, inflow = 0.0;
  double breach = 0.0, crest = 0.0, spillway = 0.0;
  double total() const { return breach + crest + spillway; }
};

class BreachState {
 public:
  explicit BreachState(const Scene& scene);

  StateVector initial() const;
  Flows flows(double t, const StateVector& y, Stage stage) const;
  // The erosion stress driving the active stage (Pa): pipe wall (0), face tau_e (1), jet stress
  // at the headcut base (2), critical-section tau_e (3, 4).
  double stress(const Flows& f, const StateVector& y, Stage stage) const;
  void derivatives(double t, const StateVector& y, Stage stage, bool width_capped, StateVector& dydt) const;

  // An event: the end of a stage, the breach reaching the crest length, or the reservoir running
  // empty. distance() is positive before it and zero at it; the integrator then sets `component`
  // to `at` exactly (except for the empty reservoir, where nothing is set: the storage is left at
  // the located value, within round-off of zero, so the mass balance stays exact).
  //
  // A switch is a point where the right-hand side has a kink without any state changing: the
  // level crossing the crest, the breach invert or the spillway crest (an outflow starts or
  // stops), the active erosion stress crossing tau_c (erosion starts or stops). The error
  // estimate of a step across a kink is unreliable, so steps end on switches too. For a switch,
  // `at` is the sign the switch function had at the start of the step and `index` says which.
  struct Event {
    enum class Kind { stage_end, width_cap, empty_reservoir, switch_point } kind;
    Component component;
    double at;
    int index = 0;
  };
  Event stage_end(Stage stage) const;
  Event width_cap() const { return {Event::Kind::width_cap, kBottomWidth, scene_.dam.crest_length}; }
  Event empty_reservoir() const { return {Event::Kind::empty_reservoir, kStorageLessInflow, 0.0}; }
  // The switch functions (their zeros are the switches), each scaled to a length or a stress.
  static constexpr int kSwitches = 4;
  std::array<double, kSwitches> switches(double t, const StateVector& y, Stage stage) const;
  // How close to zero a switch function counts as on the switch.
  double switch_tolerance(int index) const;
  Stage first_stage() const;
  double distance(const Event& e, double t, const StateVector& y, Stage stage) const;
  double storage(double t, const StateVector& y) const {
    return y[kStorageLessInflow] + (scene_.inflow.cumulative(t) - inflow_at_start_);
  }

  // The pipe's roof collapses (the end of stage 0): the invert and bottom width of y become the
  // breach's at the top of the roof's debris (InternalErosion::debris_bulking).
  void collapse_roof(StateVector& y) const;
  double headcut_height(const StateVector& y) const;
  double invert(const StateVector& y, Stage stage) const;
  double top_width(const StateVector& y, Stage stage) const;
  // Soil removed so far: the pipe (0), the face strip (1), the headcut channel (2), plus the
  // breach cut through the embankment (3, 4). Exact for the model's geometry.
  double eroded_volume(const StateVector& y, Stage stage) const;
  // Typical magnitudes of the components, for the integrator's absolute tolerances.
  StateVector scales() const;
  const Scene& scene() const { return scene_; }

 private:
  const Scene& scene_;
  double inflow_at_start_ = 0.0;  // hydrograph.cumulative(time.start)
  double pipe_length(const StateVector& y) const {
    return scene_.dam.streamwise_length(y[kInvert] + 0.5 * y[kBottomWidth]);
  }
};

}  // namespace suite::breach
