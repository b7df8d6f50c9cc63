#include "solvers/breach/model/scene.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace suite::breach {

namespace {

Reservoir read_reservoir(const config::Section& s, const Embankment& dam) {
  Reservoir r;
  r.storage = StageStorage::read(s.section("storage"));
  r.initial_level = s.quantity("initial_level", "m");
  if (r.initial_level < r.storage.bottom())
    s.reject("initial_level", fmt::format("is below the bottom of the storage relation ({} m)", r.storage.bottom()));
  if (r.initial_level > dam.crest() + dam.height)
    s.reject("initial_level", fmt::format("is more than a dam height above the crest ({} m); check the datum "
                                          "(levels and dam.foundation use the same one)",
                                          dam.crest()));
  if (auto sp = s.optional_section("spillway")) r.spillway = RatingCurve::read(*sp);
  return r;
}

BreachSettings read_breach(const config::Section& b, const config::Section& h, const Embankment& dam,
                           const Soil& soil) {
  using config::Range;
  BreachSettings out;
  out.initial_width = b.quantity("initial_width", "m", std::min(dam.height, dam.crest_length), Range::positive());
  if (out.initial_width > dam.crest_length)
    b.reject("initial_width", fmt::format("is wider than the crest ({} m)", dam.crest_length));
  out.side_slope = b.number("side_slope", 1.0, Range::at_least(0));
  out.face_roughness = b.number("face_roughness", soil.grain_roughness, Range::at_least(soil.grain_roughness));
  out.formation_depth = h.quantity("formation_depth", "m", 0.1 * dam.height, Range::positive());
  if (out.formation_depth >= dam.height) h.reject("formation_depth", "must be less than the dam height");
  out.headcut.jet_friction = h.number("jet_friction", out.headcut.jet_friction, Range::positive());
  out.headcut.jet_diffusion = h.number("jet_diffusion", out.headcut.jet_diffusion, Range::positive());
  out.headcut.critical_height_factor =
      h.number("critical_height_factor", out.headcut.critical_height_factor, Range::positive());
  return out;
}

InternalErosion read_internal_erosion(const config::Section& s, const Embankment& dam) {
  using config::Range;
  InternalErosion ie;
  ie.enabled = true;
  ie.elevation = s.quantity("elevation", "m");
  if (ie.elevation < dam.foundation || ie.elevation >= dam.crest())
    s.reject("elevation",
             fmt::format("must be between the foundation ({} m) and the crest ({} m)", dam.foundation, dam.crest()));
  ie.initial_diameter = s.quantity("initial_diameter", "m", ie.initial_diameter, Range::positive());
  ie.entrance_loss = s.number("entrance_loss", ie.entrance_loss, Range::at_least(0));
  ie.collapse_fraction = s.number("collapse_fraction", ie.collapse_fraction, Range::between(0.05, 1.0));
  if (ie.initial_diameter >= ie.geometric_collapse_diameter(dam.crest()))
    s.reject("initial_diameter", fmt::format("is already at the collapse diameter ({:.4g} m = collapse_fraction x "
                                             "height of the crest above the pipe)",
                                             ie.geometric_collapse_diameter(dam.crest())));
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
  sc.reservoir = read_reservoir(root.section("reservoir"), sc.dam);
  sc.inflow = Hydrograph::read(root.section("inflow"));
  sc.breach = read_breach(root.section_or_empty("breach"), root.section_or_empty("headcut"), sc.dam, sc.soil);
  if (auto ie = root.optional_section("internal_erosion")) sc.internal_erosion = read_internal_erosion(*ie, sc.dam);
  sc.time = read_time(root.section("time"));
  const double span = sc.time.end - sc.time.start;
  sc.output_interval =
      root.section_or_empty("output").quantity("interval", "s", span / 1000.0, Range::at_least(span / 1e6));
  return sc;
}

Scene Scene::read_complete(const config::Config& cfg) {
  Scene scene = read(cfg.root());
  cfg.root().section_or_empty("output").get<bool>("plot", true);
  cfg.finish();
  return scene;
}

}  // namespace suite::breach
