#include "solvers/breach/model/breach_state.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "solvers/breach/erosion/excess_stress.hpp"
#include "solvers/breach/hydraulics/open_channel.hpp"
#include "solvers/breach/hydraulics/pipe_flow.hpp"
#include "solvers/breach/hydraulics/weir.hpp"

namespace suite::breach {

BreachState::BreachState(const Scene& scene)
    : scene_(scene), inflow_at_start_(scene.inflow.cumulative(scene.time.start)) {}

Stage BreachState::first_stage() const {
  return scene_.internal_erosion.enabled ? Stage::internal_erosion : Stage::surface_erosion;
}

StateVector BreachState::initial() const {
  StateVector y{};
  y[kStorageLessInflow] = scene_.reservoir.storage.volume(scene_.reservoir.initial_level);
  const InternalErosion& ie = scene_.internal_erosion;
  y[kInvert] = ie.enabled ? ie.elevation : scene_.dam.crest();
  y[kBottomWidth] = ie.enabled ? ie.initial_diameter : scene_.breach.initial_width;
  return y;
}

double BreachState::invert(const StateVector& y, Stage stage) const {
  return stage >= Stage::breach_formation ? y[kInvert] : scene_.dam.crest();
}

double BreachState::top_width(const StateVector& y, Stage stage) const {
  if (stage == Stage::internal_erosion) return 0.0;  // the crest is intact above the pipe
  if (stage < Stage::breach_formation) return y[kBottomWidth];
  return y[kBottomWidth] + 2.0 * scene_.breach.side_slope * (scene_.dam.crest() - y[kInvert]);
}

Flows BreachState::flows(double t, const StateVector& y, Stage stage) const {
  const Scene& sc = scene_;
  Flows f;
  f.inflow = sc.inflow(t);
  f.storage = storage(t, y);
  f.level = sc.reservoir.storage.level(std::max(f.storage, 0.0));
  if (f.storage <= 0.0) return f;  // an empty reservoir releases nothing, whatever lies below it
  // Before the breach forms, the concentrated flow passes a rectangular notch at crest level;
  // afterwards a trapezoid whose side slopes carry flow too, but only below the crest level: the
  // flow above it is crest flow, over the crest length not taken by the breach's top width. (The
  // side term is c2 s (h^2.5 - h_crest^2.5), so the outflow is continuous at breach initiation.)
  if (stage == Stage::internal_erosion) {
    const double d = y[kBottomWidth];
    f.breach = pipe_discharge(d, pipe_length(y), f.level - (y[kInvert] + 0.5 * d), sc.soil.grain_roughness,
                              sc.internal_erosion.entrance_loss, sc.gravity);
  } else {
    const double zb = invert(y, stage);
    const double s = stage >= Stage::breach_formation ? sc.breach.side_slope : 0.0;
    f.breach = weir_discharge(y[kBottomWidth], s, f.level - zb, sc.gravity) -
               weir_discharge(0.0, s, f.level - sc.dam.crest(), sc.gravity);
  }
  const double rest = std::max(sc.dam.crest_length - top_width(y, stage), 0.0);
  f.crest = weir_discharge(rest, 0.0, f.level - sc.dam.crest(), sc.gravity);
  f.spillway = sc.reservoir.spillway(f.level);
  return f;
}

void BreachState::collapse_roof(StateVector& y) const {
  // Per metre along the flow: the roof, the block of the pipe's width d from its crown to the
  // crest, falls into the pipe and the void moves up to the crest (a sinkhole). In the d-wide
  // trench from the pipe's invert to the crest (depth H) the soil beside the pipe stays, d^2 -
  // pi d^2 / 4, and the roof's d (H - d) takes B times its volume: the notch left open at the
  // crest is pi d^2 / 4 - (B - 1) d (H - d) over the width d (none once the bulked roof fills
  // the trench: the collapse then plugs the pipe).
  const double d = y[kBottomWidth], depth = scene_.dam.crest() - y[kInvert];
  const double open = std::numbers::pi / 4.0 * d * d -
                      (scene_.internal_erosion.debris_bulking - 1.0) * d * std::max(depth - d, 0.0);
  y[kInvert] = scene_.dam.crest() - std::max(open, 0.0) / d;
}

double BreachState::headcut_height(const StateVector& y) const {
  return scene_.breach.formation_depth + scene_.dam.surface(y[kHeadcutPosition]) - scene_.dam.foundation;
}

double BreachState::stress(const Flows& f, const StateVector& y, Stage stage) const {
  const Scene& sc = scene_;
  const double q = f.breach / y[kBottomWidth];
  switch (stage) {
    case Stage::internal_erosion:
      return pipe_wall_stress(y[kBottomWidth], f.breach, sc.soil.grain_roughness, sc.gravity);
    case Stage::surface_erosion: {
      const double n = sc.breach.face_roughness, slope = 1.0 / sc.dam.downstream_slope;
      return effective_stress(normal_flow_stress(q, slope, n, sc.gravity), sc.soil.grain_roughness, n);
    }
    case Stage::headcut_advance:
      return jet_stress(q, headcut_height(y), std::cbrt(q * q / sc.gravity), sc.breach.headcut, sc.gravity);
    case Stage::breach_formation:
    case Stage::breach_widening:
      return critical_section_stress(y[kBottomWidth], sc.breach.side_slope, f.level - y[kInvert],
                                     sc.soil.grain_roughness, sc.gravity);
  }
  return 0.0;
}

void BreachState::derivatives(double t, const StateVector& y, Stage stage, bool width_capped, StateVector& dydt) const {
  const Scene& sc = scene_;
  const Flows f = flows(t, y, stage);
  dydt.fill(0.0);
  dydt[kStorageLessInflow] = -f.total();
  dydt[kBreachVolume] = f.breach;
  dydt[kCrestVolume] = f.crest;
  dydt[kSpillwayVolume] = f.spillway;
  switch (stage) {
    case Stage::internal_erosion:
      dydt[kBottomWidth] = 2.0 * erosion_rate(sc.soil.kd, stress(f, y, stage), sc.soil.tau_c);
      break;
    case Stage::surface_erosion:
      dydt[kFaceErosion] = erosion_rate(sc.soil.kd, stress(f, y, stage), sc.soil.tau_c);
      break;
    case Stage::headcut_advance:
      dydt[kHeadcutPosition] =
          headcut_advance_rate(f.breach / y[kBottomWidth], headcut_height(y), sc.soil, sc.breach.headcut, sc.gravity);
      break;
    case Stage::breach_formation:
    case Stage::breach_widening: {
      const double rate = erosion_rate(sc.soil.kd, stress(f, y, stage), sc.soil.tau_c);
      if (stage == Stage::breach_formation) dydt[kInvert] = -rate;
      if (!width_capped) dydt[kBottomWidth] = 2.0 * rate;
      break;
    }
  }
}

BreachState::Event BreachState::stage_end(Stage stage) const {
  constexpr auto end = Event::Kind::stage_end;
  switch (stage) {
    case Stage::internal_erosion:
      return {end, kBottomWidth,
              std::min(scene_.internal_erosion.geometric_collapse_diameter(scene_.dam.crest()),
                       scene_.breach.headcut.critical_height_factor * scene_.soil.s_u / scene_.soil.gamma_t)};
    case Stage::surface_erosion:
      return {end, kFaceErosion, scene_.breach.formation_depth};
    case Stage::headcut_advance:
      return {end, kHeadcutPosition, scene_.dam.x_crest_upstream()};
    case Stage::breach_formation:
    case Stage::breach_widening:
      break;
  }
  return {end, kInvert, scene_.dam.foundation};
}

std::array<double, BreachState::kSwitches> BreachState::switches(double t, const StateVector& y, Stage stage) const {
  const Scene& sc = scene_;
  const Flows f = flows(t, y, stage);
  const double opening = stage == Stage::internal_erosion ? y[kInvert] + 0.5 * y[kBottomWidth] : invert(y, stage);
  const double spill = sc.reservoir.spillway.empty() ? -1e300 : sc.reservoir.spillway.crest();
  return {f.level - sc.dam.crest(), f.level - opening, sc.reservoir.spillway.empty() ? 1.0 : f.level - spill,
          stage == Stage::headcut_advance ? 1.0 : stress(f, y, stage) - sc.soil.tau_c};
}

double BreachState::switch_tolerance(int index) const {
  return index < 3 ? 1e-10 * scene_.dam.height : 1e-10 * std::max(scene_.soil.tau_c, 1.0);
}

double BreachState::distance(const Event& e, double t, const StateVector& y, Stage stage) const {
  if (e.kind == Event::Kind::switch_point) return e.at * switches(t, y, stage)[static_cast<std::size_t>(e.index)];
  // Face erosion, headcut position and width grow towards the event; the invert and the
  // storage fall to it.
  if (e.component == kStorageLessInflow) return storage(t, y);
  return e.component == kInvert ? y[kInvert] - e.at : e.at - y[e.component];
}

double BreachState::eroded_volume(const StateVector& y, Stage stage) const {
  const Embankment& dam = scene_.dam;
  const double b0 = scene_.breach.initial_width;
  if (stage == Stage::internal_erosion)
    return std::numbers::pi / 4.0 * y[kBottomWidth] * y[kBottomWidth] * pipe_length(y);
  // After a pipe's collapse: the cut above the debris (no face strip or headcut channel was
  // eroded in this mode).
  if (scene_.internal_erosion.enabled) return dam.cut_volume(y[kBottomWidth], scene_.breach.side_slope, y[kInvert]);
  // The face strip of depth min(erosion, formation depth): all of the face in stage 1, the part
  // upstream of the headcut afterwards.
  if (stage == Stage::surface_erosion) return b0 * std::max(y[kFaceErosion], 0.0) * dam.downstream_face_length();
  const double per_x = std::sqrt(1.0 + 1.0 / (dam.downstream_slope * dam.downstream_slope));  // slope length / dx
  const double strip =
      b0 * scene_.breach.formation_depth * std::max(dam.x_crest_downstream() - y[kHeadcutPosition], 0.0) * per_x;
  // The headcut channel: width b0 from the toe to the headcut, floor at foundation - formation
  // depth, up to the embankment surface (or, once the breach cut exists, up to its invert).
  const double floor = dam.foundation - scene_.breach.formation_depth;
  const double x_end = y[kHeadcutPosition];
  const bool cut = stage >= Stage::breach_formation;
  const double top = cut ? y[kInvert] : dam.crest();
  std::vector<double> xs{0.0,
                         x_end,
                         dam.x_crest_downstream(),
                         dam.x_crest_upstream(),
                         dam.downstream_slope * (top - dam.foundation),
                         dam.x_crest_upstream() + dam.upstream_slope * (dam.crest() - top)};
  std::erase_if(xs, [&](double x) { return x < 0.0 || x > x_end; });
  std::sort(xs.begin(), xs.end());
  auto depth = [&](double x) { return std::min(dam.surface(x), top) - floor; };
  double channel = 0.0;  // the integrand is linear between the kinks in xs: the trapezoid rule is exact
  for (std::size_t i = 1; i < xs.size(); ++i) channel += 0.5 * (depth(xs[i - 1]) + depth(xs[i])) * (xs[i] - xs[i - 1]);
  channel *= b0;
  return strip + channel + (cut ? dam.cut_volume(y[kBottomWidth], scene_.breach.side_slope, y[kInvert]) : 0.0);
}

StateVector BreachState::scales() const {
  const double volume = std::max({scene_.reservoir.storage.volume(scene_.dam.crest()),
                                  scene_.reservoir.storage.volume(scene_.reservoir.initial_level), 1.0});
  const double length = scene_.dam.height;
  return {volume, volume, volume, volume, length, length, length, length};
}

}  // namespace suite::breach
