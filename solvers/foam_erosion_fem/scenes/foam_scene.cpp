#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace suite::foam_erosion {

namespace {

using config::Range;

Fluid read_fluid(const config::Section& s, Fluid fallback) {
  Fluid f;
  f.density = s.quantity("density", "kg/m^3", fallback.density, Range::positive());
  f.viscosity = s.quantity("viscosity", "m^2/s", fallback.viscosity, Range::positive());
  return f;
}

Domain read_domain(const config::Section& s, const breach::Embankment& dam) {
  Domain d;
  d.upstream_length = s.quantity("upstream_length", "m", 2.0 * dam.height, Range::positive());
  d.downstream_length = s.quantity("downstream_length", "m", 2.0 * dam.height, Range::positive());
  d.height = s.quantity("height", "m", 1.5 * dam.height, Range::positive());
  if (d.height <= dam.height)
    s.reject("height", fmt::format("the domain ({} m above the foundation) must be taller than the dam "
                                   "(dam.height = {} m): overtopping flow needs room above the crest; "
                                   "give at least {:.3g} m",
                                   d.height, dam.height, 1.2 * dam.height));
  return d;
}

MeshSettings read_mesh(const config::Section& s, const breach::Embankment& dam, const Domain& domain) {
  MeshSettings m;
  m.cell_size = s.quantity("cell_size", "m", Range::positive());
  const double above_crest = domain.height - dam.height;
  if (m.cell_size > 0.5 * above_crest)
    s.reject("cell_size", fmt::format("{} m leaves fewer than 2 cells between the crest and the top of the domain "
                                      "({} m); give at most {:.3g} m or raise domain.height",
                                      m.cell_size, above_crest, 0.5 * above_crest));
  if (m.cell_size > 0.25 * std::min(dam.crest_width > 0 ? dam.crest_width : dam.height, dam.height))
    s.reject("cell_size", fmt::format("{} m resolves the dam with fewer than 4 cells (height {} m, crest width "
                                      "{} m); give at most {:.3g} m",
                                      m.cell_size, dam.height, dam.crest_width,
                                      0.25 * std::min(dam.crest_width > 0 ? dam.crest_width : dam.height, dam.height)));
  m.far_cell_size = s.quantity("far_cell_size", "m", 4.0 * m.cell_size, Range::at_least(m.cell_size));
  m.vertical_grading = s.number("vertical_grading", 1.0, Range::between(0.1, 10.0));
  return m;
}

FlowSettings read_flow(const config::Section& s) {
  FlowSettings f;
  f.turbulence = s.choice("turbulence", {"laminar", "kEpsilon"}, "kEpsilon");
  f.water = read_fluid(s.section_or_empty("water"), f.water);
  f.air = read_fluid(s.section_or_empty("air"), f.air);
  f.surface_tension = s.quantity("surface_tension", "N/m", f.surface_tension, Range::at_least(0));
  f.wall_roughness = s.quantity("wall_roughness", "m", 0.0, Range::at_least(0));
  if (f.wall_roughness > 0 && f.turbulence != "kEpsilon")
    s.reject("wall_roughness",
             "a rough wall needs the turbulence model's wall function; set flow.turbulence: kEpsilon "
             "or leave wall_roughness out (laminar walls are smooth)");
  return f;
}

CouplingSettings read_coupling(const config::Section& s) {
  CouplingSettings c;
  c.interval = s.quantity("interval", "s", Range::positive());
  c.morphological_factor = s.number("morphological_factor", 1.0, Range::positive());
  return c;
}

TimeSettings read_time(const config::Section& s, const CouplingSettings& coupling) {
  TimeSettings t;
  t.end = s.quantity("end", "s", Range::positive());
  t.max_courant = s.number("max_courant", 0.5, Range{0.0, 5.0, true, false});
  t.max_alpha_courant = s.number("max_alpha_courant", 0.5, Range{0.0, 5.0, true, false});
  t.max_dt = s.quantity("max_dt", "s", coupling.interval / 10.0, Range::positive());
  if (s.has("fixed_dt")) t.fixed_dt = s.quantity("fixed_dt", "s", Range::positive());
  t.write_interval = s.quantity("write_interval", "s", coupling.interval, Range::positive());
  // The coupled loop reads the fields interFoam writes at the end of every coupling interval.
  const double writes_per_interval = coupling.interval / t.write_interval;
  if (std::abs(writes_per_interval - std::round(writes_per_interval)) > 1e-9 * writes_per_interval ||
      writes_per_interval < 1.0 - 1e-9)
    s.reject("write_interval", fmt::format("{} s does not divide coupling.interval ({} s); the coupling reads the "
                                           "fields written at the end of each interval: use {} s or a divisor of it",
                                           t.write_interval, coupling.interval, coupling.interval));
  if (t.fixed_dt && *t.fixed_dt > coupling.interval)
    s.reject("fixed_dt", fmt::format("{} s is longer than coupling.interval ({} s); the flow must take at least one "
                                     "step per erosion step",
                                     *t.fixed_dt, coupling.interval));
  return t;
}

}  // namespace

FoamScene FoamScene::read(const config::Section& root) {
  FoamScene sc;
  sc.gravity = root.quantity("gravity", "m/s^2", 9.81, Range::positive());
  sc.dam = breach::Embankment::read(root.section("dam"));

  const auto soil = root.section("soil");
  sc.soil.kd = soil.quantity("erodibility", "m^3/(N s)", Range::at_least(0));
  sc.soil.tau_c = soil.quantity("critical_shear_stress", "Pa", 0.0, Range::at_least(0));
  if (soil.has("repose_angle")) sc.soil.repose_angle = soil.quantity("repose_angle", "deg", Range{0.0, 90.0, true, true});
  if (soil.has("undrained_shear_strength"))
    sc.soil.undrained_shear_strength = soil.quantity("undrained_shear_strength", "Pa", Range::at_least(0));
  if (soil.has("unit_weight")) sc.soil.unit_weight = soil.quantity("unit_weight", "N/m^3", Range::positive());

  sc.domain = read_domain(root.section_or_empty("domain"), sc.dam);
  const auto reservoir = root.section("reservoir");
  sc.initial_level = reservoir.quantity("initial_level", "m");
  if (sc.initial_level < sc.dam.foundation || sc.initial_level >= sc.top())
    reservoir.reject("initial_level", fmt::format("the reservoir must lie between the foundation ({} m) and the "
                                                  "top of the domain ({} m)",
                                                  sc.dam.foundation, sc.top()));
  if (sc.initial_level < sc.dam.foundation + 0.1 * sc.dam.height)
    reservoir.reject("initial_level", fmt::format("the reservoir must wet the inlet: interFoam's flow-rate inlet spreads "
                                                  "the inflow over the wet part of the inlet; give at least {:.3g} m "
                                                  "(a tenth of the dam height above the foundation)",
                                                  sc.dam.foundation + 0.1 * sc.dam.height));
  if (reservoir.has("tailwater_level")) {
    sc.tailwater_level = reservoir.quantity("tailwater_level", "m");
    if (*sc.tailwater_level < sc.dam.foundation || *sc.tailwater_level >= sc.dam.crest())
      reservoir.reject("tailwater_level", fmt::format("the tailwater must lie between the foundation ({} m) and the "
                                                      "crest ({} m)",
                                                      sc.dam.foundation, sc.dam.crest()));
  }
  sc.inflow = Hydrograph::read(root.section("inflow"));

  sc.mesh = read_mesh(root.section("mesh"), sc.dam, sc.domain);
  sc.flow = read_flow(root.section_or_empty("flow"));
  sc.coupling = read_coupling(root.section("coupling"));
  sc.time = read_time(root.section("time"), sc.coupling);
  if (sc.soil.kd > 0 && sc.coupling.interval > sc.time.end)
    root.section("coupling").reject("interval", fmt::format("{} s is longer than time.end ({} s): no erosion step "
                                                            "would run",
                                                            sc.coupling.interval, sc.time.end));
  if (sc.soil.kd > 0) {
    // Every interval ends on one of OpenFOAM's write times, where the wall shear stress is read:
    // a shorter last interval would end between them.
    const double n = sc.time.end / sc.coupling.interval;
    if (std::abs(n - std::round(n)) > 1e-9 * n)
      root.section("coupling").reject(
          "interval", fmt::format("{} s does not divide time.end ({} s) into whole intervals; give {:.6g} s or {:.6g} "
                                  "s",
                                  sc.coupling.interval, sc.time.end, sc.time.end / std::ceil(n),
                                  sc.time.end / std::max(1.0, std::floor(n))));
  }

  const auto run = root.section_or_empty("run");
  sc.run.ranks = static_cast<int>(run.integer("ranks", 1, 1, 4096));
  sc.run.decomposition = run.choice("decomposition", {"simple", "hierarchical"}, "simple");
  return sc;
}

}  // namespace suite::foam_erosion
