#include "solvers/breach/model/scene.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace suite::breach {

namespace {

Reservoir read_reservoir(const config::Section& s) {
  Reservoir r;
  r.storage = StageStorage::read(s.section("storage"));
  r.initial_level = s.quantity("initial_level", "m");
  if (auto sp = s.optional_section("spillway")) r.spillway = RatingCurve::read(*sp);
  return r;
}

BreachSettings read_breach(const config::Section& b, const config::Section& h, const Embankment& dam,
                           const Soil& soil) {
  using config::Range;
  BreachSettings out;
  out.initial_width = b.quantity("initial_width", "m", BreachSettings::default_initial_width(dam), Range::positive());
  out.side_slope = b.number("side_slope", 1.0, Range::at_least(0));
  out.face_roughness = b.number("face_roughness", soil.grain_roughness, Range::at_least(soil.grain_roughness));
  out.formation_depth =
      h.quantity("formation_depth", "m", BreachSettings::default_formation_depth(dam), Range::positive());
  out.headcut.jet_friction = h.number("jet_friction", out.headcut.jet_friction, Range::positive());
  out.headcut.jet_diffusion = h.number("jet_diffusion", out.headcut.jet_diffusion, Range::positive());
  out.headcut.critical_height_factor =
      h.number("critical_height_factor", out.headcut.critical_height_factor, Range::positive());
  return out;
}

InternalErosion read_internal_erosion(const config::Section& s) {
  using config::Range;
  InternalErosion ie;
  ie.enabled = true;
  ie.elevation = s.quantity("elevation", "m");
  ie.initial_diameter = s.quantity("initial_diameter", "m", ie.initial_diameter, Range::positive());
  ie.entrance_loss = s.number("entrance_loss", ie.entrance_loss, Range::at_least(0));
  ie.collapse_fraction = s.number("collapse_fraction", ie.collapse_fraction, Range::between(0.05, 1.0));
  ie.debris_bulking = s.number("debris_bulking", ie.debris_bulking, Range::between(1.0, 2.0));
  return ie;
}

TimeSettings read_time(const config::Section& s) {
  using config::Range;
  TimeSettings t;
  t.start = s.quantity("start", "s", 0.0);
  t.end = s.quantity("end", "s");
  if (t.end <= t.start) s.reject("end", fmt::format("must be after time.start ({} s)", t.start));
  t.adaptive = s.choice("step", {"adaptive", "fixed"}, "adaptive") == "adaptive";
  if (t.adaptive) {
    t.tolerance = s.number("tolerance", 1e-6, Range::between(1e-13, 1e-1));
    t.max_step = s.quantity("max_step", "s", (t.end - t.start) / 50.0, Range::positive());
  } else {
    t.fixed_step = s.quantity("dt", "s", Range::positive());
    t.max_step = t.fixed_step;
  }
  return t;
}

}  // namespace

Scene Scene::read(const config::Section& root) {
  using config::Range;
  Scene sc;
  sc.gravity = root.quantity("gravity", "m/s^2", 9.81, Range::positive());
  sc.dam = Embankment::read(root.section("dam"));
  sc.soil = Soil::read(root.section("soil"));
  sc.reservoir = read_reservoir(root.section("reservoir"));
  sc.inflow = Hydrograph::read(root.section("inflow"));
  sc.breach = read_breach(root.section_or_empty("breach"), root.section_or_empty("headcut"), sc.dam, sc.soil);
  if (auto ie = root.optional_section("internal_erosion")) sc.internal_erosion = read_internal_erosion(*ie);
  sc.time = read_time(root.section("time"));
  const double span = sc.time.end - sc.time.start;
  sc.output_interval =
      root.section_or_empty("output").quantity("interval", "s", span / 1000.0, Range::at_least(span / 1e6));
  if (const auto p = sc.cross_section_problem()) root.section(p->section).reject(p->key, p->text);
  return sc;
}

std::optional<Scene::Problem> Scene::cross_section_problem() const {
  const double crest = dam.crest();
  if (breach.initial_width > dam.crest_length)
    return Problem{"breach", "initial_width", fmt::format("is wider than the crest ({} m)", dam.crest_length)};
  if (breach.formation_depth >= dam.height)
    return Problem{"headcut", "formation_depth", "must be less than the dam height"};
  // The breach can erode down to the foundation; a storage relation that ends above it would
  // give the reservoir negative storage there (and the model water that never was).
  if (reservoir.storage.bottom() > dam.foundation)
    return Problem{"reservoir", "storage",
                   fmt::format("has its bottom (zero storage) at {} m, above the dam's foundation ({} m), down to "
                               "which the breach can erode; give the storage relation's bottom at or below the "
                               "foundation, in the dam's datum",
                               reservoir.storage.bottom(), dam.foundation)};
  if (reservoir.initial_level < reservoir.storage.bottom())
    return Problem{"reservoir", "initial_level",
                   fmt::format("is below the bottom of the storage relation ({} m)", reservoir.storage.bottom())};
  if (reservoir.initial_level > crest + dam.height)
    return Problem{"reservoir", "initial_level",
                   fmt::format("is more than a dam height above the crest ({} m); check the datum (levels and "
                               "dam.foundation use the same one)",
                               crest)};
  if (!internal_erosion.enabled) return std::nullopt;
  if (internal_erosion.elevation < dam.foundation || internal_erosion.elevation >= crest)
    return Problem{"internal_erosion", "elevation",
                   fmt::format("must be between the foundation ({} m) and the crest ({} m)", dam.foundation, crest)};
  if (internal_erosion.initial_diameter >= internal_erosion.geometric_collapse_diameter(crest))
    return Problem{"internal_erosion", "initial_diameter",
                   fmt::format("is already at the collapse diameter ({:.4g} m = collapse_fraction x height of the "
                               "crest above the pipe)",
                               internal_erosion.geometric_collapse_diameter(crest))};
  return std::nullopt;
}

Scene Scene::read_complete(const config::Config& cfg) {
  Scene scene = read(cfg.root());
  cfg.root().section_or_empty("output").get<bool>("plot", true);
  cfg.finish();
  return scene;
}

}  // namespace suite::breach
