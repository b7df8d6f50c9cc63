#pragma once
// Everything one coupled OpenFOAM + FEM erosion run needs, read from a scene (YAML):
//
//   gravity: 9.81 m/s^2
//   dam:       {height, crest_width, crest_length, upstream_slope, downstream_slope, foundation}
//              the breach model's description (solvers/breach/geometry/embankment.hpp): the same
//              block runs in both; slopes H:V
//   soil:      {erodibility, critical_shear_stress, repose_angle,   # kd, tau_c; repose optional
//               undrained_shear_strength, unit_weight}              # optional: the breach model
//   reservoir: {initial_level, tailwater_level}                     # tailwater optional
//   inflow:    the breach model's `inflow` section (core/tables/hydrograph.hpp): total discharge over the
//              crest length; the 2D case carries q = Q / crest_length per metre
//   domain:    {upstream_length, downstream_length, height}         # height above the foundation
//   mesh:      {cell_size, far_cell_size, vertical_grading}
//   flow:      {turbulence: laminar | kEpsilon, water: {density, viscosity},
//               air: {density, viscosity}, surface_tension, wall_roughness}
//   time:      {end, max_courant, max_alpha_courant, max_dt, fixed_dt, write_interval}
//   coupling:  {interval, morphological_factor}
//   run:       {ranks, decomposition: simple | hierarchical}
//
// Coordinates of the case: x downstream from the inlet, y up (levels on the dam's datum, so the
// foundation is at y = dam.foundation), z across the one-cell-thick slab.
#include <optional>
#include <string>

#include "core/config/config.hpp"
#include "solvers/breach/geometry/embankment.hpp"
#include "core/tables/hydrograph.hpp"

namespace suite::foam_erosion {

struct Domain {
  double upstream_length = 0.0;    // inlet to upstream toe, m
  double downstream_length = 0.0;  // downstream toe to outlet, m
  double height = 0.0;             // top of the domain above the foundation, m
};

struct MeshSettings {
  double cell_size = 0.0;         // on and above the dam, m
  double far_cell_size = 0.0;     // at the inlet and outlet (the floor cells grow towards them), m
  double vertical_grading = 1.0;  // top cell height / bottom cell height of the background mesh
};

struct Fluid {
  double density = 0.0;    // kg/m^3
  double viscosity = 0.0;  // kinematic, m^2/s
};

struct FlowSettings {
  std::string turbulence = "kEpsilon";  // or "laminar"
  Fluid water{1000.0, 1.0e-6};
  Fluid air{1.0, 1.48e-5};
  double surface_tension = 0.07;  // N/m
  // Equivalent sand-grain roughness k_s of the dam and the floor, m (kEpsilon only). 0: smooth
  // walls (nutkWallFunction); > 0: nutkRoughWallFunction with Ks = k_s, Cs = 0.5 (Nikuradse's
  // sand), the wall law a Manning n stands for: k_s = (21.1 n)^6 (Strickler), e.g. n = 0.016
  // s/m^(1/3) is k_s = 1.5 mm.
  double wall_roughness = 0.0;
};

struct TimeSettings {
  double end = 0.0;                // simulated flow time, s
  double max_courant = 0.5;        // interFoam maxCo
  double max_alpha_courant = 0.5;  // interFoam maxAlphaCo (interface)
  double max_dt = 0.0;             // s; default: the coupling interval / 10
  std::optional<double> fixed_dt;  // s; fixed deltaT (the dissertation's Table 3.2 runs)
  double write_interval = 0.0;     // s; OpenFOAM time directories
};

struct SoilErosion {
  double kd = 0.0;                       // m^3/(N s)
  double tau_c = 0.0;                    // Pa
  std::optional<double> repose_angle;    // degrees
  // Only for the breach-model run beside the coupled one (run/breach_comparison.hpp): its headcut
  // needs them. Without both there is no comparison.
  std::optional<double> undrained_shear_strength;  // s_u, Pa
  std::optional<double> unit_weight;               // gamma_t, N/m^3
};

struct CouplingSettings {
  double interval = 0.0;              // flow time between erosion steps, s
  double morphological_factor = 1.0;  // erosion time = factor x flow time
};

struct RunSettings {
  int ranks = 1;
  std::string decomposition = "simple";  // simple | hierarchical (Debian's scotch/metis are stubs)
};

struct FoamScene {
  double gravity = 9.81;
  breach::Embankment dam;
  SoilErosion soil;
  double initial_level = 0.0;
  std::optional<double> tailwater_level;
  Hydrograph inflow = Hydrograph::constant(0.0);  // total m^3/s over crest_length
  Domain domain;
  MeshSettings mesh;
  FlowSettings flow;
  TimeSettings time;
  CouplingSettings coupling;
  RunSettings run;

  // Reads and checks the whole scene (InputError names the key); does not call finish().
  static FoamScene read(const config::Section& root);

  double top() const { return dam.foundation + domain.height; }
  // Discharge per metre of crest (m^2/s) at time t.
  double unit_discharge(double t) const { return inflow(t) / dam.crest_length; }
};

}  // namespace suite::foam_erosion
