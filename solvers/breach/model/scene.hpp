#pragma once
// Everything one breach run needs, read from a scene (YAML) with units per quantity:
//
//   gravity: 9.81 m/s^2              # optional
//   dam:       {height, crest_width, crest_length, upstream_slope, downstream_slope, foundation}
//   soil:      {erodibility, critical_shear_stress, undrained_shear_strength, unit_weight,
//               grain_roughness | d75}
//   reservoir: {storage: {...}, initial_level: 11 m, spillway: {table: [...]}}   # spillway optional
//   inflow:    {type: table | constant | sine | triangular, ...}
//   breach:    {initial_width, side_slope, face_roughness}                       # all optional
//   headcut:   {formation_depth, jet_friction, jet_diffusion, critical_height_factor}  # optional
//   internal_erosion: {elevation, initial_diameter, entrance_loss, collapse_fraction, debris_bulking}  # optional:
//              the breach starts from a pipe instead of from overtopping
//   time:      {start, end, step: adaptive | fixed, tolerance, dt, max_step}
//   output:    {interval}                                                         # executable only
//
// The sections' own headers (embankment.hpp, soil.hpp, stage_storage.hpp, rating_curve.hpp,
// core/tables/hydrograph.hpp, headcut.hpp) describe their keys and the sources of their coefficients.
#include <algorithm>
#include <optional>
#include <string>

#include "core/config/config.hpp"
#include "solvers/breach/erosion/headcut.hpp"
#include "solvers/breach/geometry/embankment.hpp"
#include "core/tables/hydrograph.hpp"
#include "solvers/breach/hydrology/rating_curve.hpp"
#include "solvers/breach/hydrology/stage_storage.hpp"
#include "solvers/breach/soil/soil.hpp"

namespace suite::breach {

struct Reservoir {
  StageStorage storage = StageStorage::power_law(1.0, 0.0, 1.0);
  double initial_level = 0.0;  // m
  RatingCurve spillway;
};

struct BreachSettings {
  // Width (m) of the concentrated flow in which the headcut forms and advances, and the breach's
  // bottom width when it starts to lower. Not fixed by the literature: default one dam height,
  // capped at the crest length (DL Breach suggests a 1-5 m pilot channel, Wu 2016).
  double initial_width = 0.0;
  // Breach side slopes, H:V. Default 1.0: Froehlich's (2008) average for overtopping failures.
  double side_slope = 1.0;
  // Total Manning n of the downstream face (grain + form + vegetation). Default: the soil's grain
  // roughness (bare, smooth face), which makes tau_e = tau_0.
  double face_roughness = 0.0;
  // Eroded depth on the downstream face at which the headcut forms at the toe (stage I -> II).
  // Not published; default 10% of the dam height (an assumption, an input).
  double formation_depth = 0.0;
  HeadcutCoefficients headcut;

  // The defaults that follow the dam: a scene that gives no width or formation depth gets these.
  static double default_initial_width(const Embankment& dam) { return std::min(dam.height, dam.crest_length); }
  static double default_formation_depth(const Embankment& dam) { return 0.1 * dam.height; }
};

// Breach initiation by internal erosion (WinDAM C's second mode; the dissertation's synthetic
// study started it at a quarter of the dam height): a pipe with its invert at `elevation` grows
// at 2 kd (tau - tau_c) under the pipe-flow wall stress (pipe_flow.hpp) until its roof collapses,
// then the breach forms from its invert with the pipe's diameter as bottom width.
struct InternalErosion {
  bool enabled = false;
  double elevation = 0.0;         // m, pipe invert
  double initial_diameter = 0.1;  // m; not published: an input (default an assumption)
  double entrance_loss = 0.5;     // K_e of a square-edged entrance (Henderson 1966)
  // The roof collapses when the pipe's diameter reaches this fraction of the embankment height
  // above its invert (0.5: the roof is then as thick as the pipe is wide), or earlier, when the
  // pipe's unsupported wall, d high, passes the critical height of a vertical cut in the soil,
  // N s_u / gamma_t (the headcut's stability number, headcut.hpp; Taylor 1948). Both are
  // assumptions: the criterion WinDAM C uses is not in the sources at hand. A pipe that starts
  // at or above the strength limit collapses at once.
  double collapse_fraction = 0.5;
  // The collapsed roof stays in the breach as debris: the roof (the block of the pipe's width
  // from its crown to the crest) falls into the pipe, taking this factor times its in-place
  // volume (loose over in-place, >= 1), and the void moves up to the crest; the breach forms
  // from the debris top, a notch of the pipe's width, and the flow erodes the debris like the
  // embankment. 1 (no bulking): the notch has the pipe's cross-section area, pi d / 4 deep. An
  // assumption (docs/breach.md), an input.
  double debris_bulking = 1.0;
  double geometric_collapse_diameter(double crest) const { return collapse_fraction * (crest - elevation); }
};

struct TimeSettings {
  double start = 0.0, end = 0.0;  // s
  bool adaptive = true;
  double tolerance = 1e-6;  // relative error per step (adaptive)
  double fixed_step = 0.0;  // s (fixed)
  double max_step = 0.0;    // s, cap on the adaptive step
};

struct Scene {
  double gravity = 9.81;
  Embankment dam;
  Soil soil;
  Reservoir reservoir;
  Hydrograph inflow = Hydrograph::constant(0.0);
  BreachSettings breach;
  InternalErosion internal_erosion;
  TimeSettings time;
  double output_interval = 0.0;  // s, between rows of the time series (default: 1000 rows)

  // Reads the whole scene (the caller calls cfg.finish() after any keys of its own).
  // InputError names the key and the fix.
  static Scene read(const config::Section& root);
  // Reads the scene of a run that writes no charts (library calls, the Dakota driver): accepts
  // the executable's own `output.plot` key, then checks that no key is left unknown.
  static Scene read_complete(const config::Config& cfg);

  // A check between keys of different sections that the scene fails: a breach wider than the
  // crest, a formation depth as deep as the dam, a pool below its storage's bottom or more than
  // a dam height above the crest, a pipe outside the embankment or already at its collapse
  // diameter.
  struct Problem {
    std::string section, key, text;  // e.g. "breach", "initial_width", "is wider than the crest (150 m)"
  };
  // The first such problem, or none. Scene::read makes these checks after reading every
  // section, and SceneVariants (scene_variants.hpp) again after changing keys, so a check
  // between sections belongs here.
  std::optional<Problem> cross_section_problem() const;
};

}  // namespace suite::breach
