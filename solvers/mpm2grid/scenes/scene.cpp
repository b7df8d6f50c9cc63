#include "solvers/mpm2grid/scenes/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "solvers/mpm2grid/scenes/initial_state.hpp"
#include "solvers/mpm2grid/scenes/read_inlet.hpp"

namespace suite::mpm2grid {
namespace {

using config::Range;

constexpr const char* kAxes = "xyz";

std::vector<double> point(const config::Section& s, const std::string& key, int dim) {
  const auto v = s.get<std::vector<double>>(key);
  if (static_cast<int>(v.size()) != dim) s.reject(key, fmt::format("give {} coordinates in m", dim));
  for (double x : v)
    if (!std::isfinite(x)) s.reject(key, "coordinates must be finite numbers");
  return v;
}

// `soil`: the region belongs to the soil and may say `saturated` (water regions may not), which
// needs the scene's water section (`water`) for the pore water's density and bulk modulus.
Region read_region(const config::Section& s, int dim, double floor, bool soil, bool water) {
  Region r;
  // Read only when given, so that the default does not enter the region's section (whose value
  // the region errors quote on one line).
  if (soil && s.has("saturated")) r.saturated = s.get<bool>("saturated");
  if (soil && s.has("surcharge")) r.surcharge = s.quantity("surcharge", "Pa", Range::at_least(0));
  if (r.saturated && !water)
    s.reject("saturated", "a saturated soil region needs the water: section (density, bulk_modulus) for its "
                          "pore water; add it, or drop saturated: true");
  const bool box = s.has("box"), trapezoid = s.has("trapezoid");
  if (box == trapezoid) s.reject(box ? "trapezoid" : "box", "give exactly one of box: {lo, hi} or trapezoid: {...}");
  if (box) {
    const auto b = s.section("box");
    r.lo = point(b, "lo", dim);
    r.hi = point(b, "hi", dim);
    for (int d = 0; d < dim; ++d)
      if (!(r.hi[d] > r.lo[d])) b.reject("hi", fmt::format("must exceed lo along {}", kAxes[d]));
    return r;
  }
  const auto t = s.section("trapezoid");
  r.kind = Region::Kind::trapezoid;
  r.toe = t.quantity("toe", "m");
  r.height = t.quantity("height", "m", Range::positive());
  r.crest_width = t.quantity("crest_width", "m", Range::at_least(0));
  r.upstream_slope = t.number("upstream_slope", Range::positive());
  r.downstream_slope = t.number("downstream_slope", Range::positive());
  r.floor = floor;
  return r;
}

std::vector<Region> read_regions(const config::Section& species, int dim, double floor, bool soil = false,
                                 bool water = false) {
  std::vector<Region> regions;
  for (const auto& s : species.sections("regions")) regions.push_back(read_region(s, dim, floor, soil, water));
  return regions;
}

// The soil's erosion model: the dissertation's cohesion falling with the saturation (the default),
// or the excess-stress rate kd (tau - tau_c) under the bed shear, with the breach model's keys and
// units (solvers/breach/soil/soil.hpp) and the detached soil's settling velocity.
void read_erosion(const config::Section& soil, ExcessStressSettings& e) {
  e.on = soil.choice("erosion", {"saturation_cohesion", "excess_stress"}, "saturation_cohesion") == "excess_stress";
  for (const char* key : {"erodibility", "critical_shear_stress", "settling_velocity"})
    if (!e.on && soil.has(key))
      soil.reject(key, "belongs to the excess-stress erosion; add erosion: excess_stress or drop it");
  if (!e.on) return;
  e.kd = soil.quantity("erodibility", "m^3/(N s)", Range::at_least(0));
  e.tau_c = soil.quantity("critical_shear_stress", "Pa", 0.0, Range::at_least(0));
  e.settling_velocity = soil.quantity("settling_velocity", "m/s", Range::at_least(0));
}

WallKind wall_kind(const config::Section& walls, const std::string& key) {
  const auto k = walls.choice(key, {"slip", "sticky", "friction", "open"}, "slip");
  return k == "slip" ? WallKind::slip : k == "sticky" ? WallKind::sticky : k == "friction" ? WallKind::friction
                                                                                            : WallKind::open;
}

template <int Dim>
void check_inside(const config::Section& s, const Region& r, const Vec<Dim>& lo, const Vec<Dim>& hi,
                  const std::string& what) {
  if (r.kind == Region::Kind::box) {
    for (int d = 0; d < Dim; ++d)
      if (r.lo[d] < lo[d] || r.hi[d] > hi[d])
        s.reject("regions", fmt::format("{} box [{}, {}] along {} leaves the domain [{}, {}]", what, r.lo[d], r.hi[d],
                                        kAxes[d], lo[d], hi[d]));
    return;
  }
  const double right = r.toe + r.height / r.upstream_slope + r.crest_width + r.height / r.downstream_slope;
  if (r.toe < lo[0] || right > hi[0] || r.floor + r.height > hi[1])
    s.reject("regions", fmt::format("{} trapezoid (x from {} to {:.4g} m, top at y = {:.4g} m) leaves the domain "
                                    "x in [{}, {}], y up to {}; move the toe or enlarge the domain",
                                    what, r.toe, right, r.floor + r.height, lo[0], hi[0], hi[1]));
}

}  // namespace

template <int Dim>
bool Region::contains(const Vec<Dim>& x, double margin) const {
  if (kind == Kind::box) {
    for (int d = 0; d < Dim; ++d)
      if (x[d] < lo[d] - margin || x[d] >= hi[d] + margin) return false;
    return true;
  }
  const double y = x[1] - floor;
  if (y < -margin || y >= height + margin) return false;
  const double yc = std::clamp(y, 0.0, height);  // = y without a margin
  const double left = toe + yc / upstream_slope;
  const double right = toe + height / upstream_slope + crest_width + (height - yc) / downstream_slope;
  return x[0] >= left - margin && x[0] < right + margin;
}

double Region::trapezoid_area() const {
  return height * (crest_width + 0.5 * height / upstream_slope + 0.5 * height / downstream_slope);
}

int scene_dimension(const config::Config& scene) {
  return static_cast<int>(scene.root().integer("dimension", 2, 2, 3));
}

template <int Dim>
Scene<Dim> read_scene(const config::Config& cfg) {
  const auto root = cfg.root();
  Scene<Dim> sc;
  sc.name = cfg.source_name();
  if (scene_dimension(cfg) != Dim) root.reject("dimension", fmt::format("this reader is for {}D scenes", Dim));
  auto& sim = sc.simulation;

  const auto grid = root.section("grid");
  sim.h = grid.quantity("spacing", "m", Range::positive());
  sc.particles_per_cell = static_cast<int>(grid.integer("particles_per_cell", 2, 1, 8));

  const auto domain = root.section("domain");
  const auto lo = point(domain, "lo", Dim), hi = point(domain, "hi", Dim);
  for (int d = 0; d < Dim; ++d) {
    sim.walls.lo[d] = lo[d], sim.walls.hi[d] = hi[d];
    if (!(hi[d] > lo[d])) domain.reject("hi", fmt::format("must exceed lo along {}", kAxes[d]));
    for (double v : {lo[d], hi[d]})
      if (std::abs(v / sim.h - std::round(v / sim.h)) > 1e-6)
        domain.reject(v == lo[d] ? "lo" : "hi",
                      fmt::format("{} = {} m is not a multiple of grid.spacing = {} m: walls act on grid planes",
                                  kAxes[d], v, sim.h));
  }

  const auto walls = root.section_or_empty("walls");
  for (int d = 0; d < Dim; ++d) {
    sim.walls.kind[d][0] = wall_kind(walls, fmt::format("{}_low", kAxes[d]));
    sim.walls.kind[d][1] = wall_kind(walls, fmt::format("{}_high", kAxes[d]));
  }
  sim.walls.friction = root.number("wall_friction", 0.3, Range::at_least(0));

  sim.gravity.setZero();
  sim.gravity[1] = -root.quantity("gravity", "m/s^2", 9.81, Range::at_least(0));

  if (const auto w = root.optional_section("water")) {
    sim.water.density = w->quantity("density", "kg/m^3", 1000.0, Range::positive());
    sim.water.eos.bulk_modulus = w->quantity("bulk_modulus", "Pa", Range::positive());
    sim.water.eos.gamma = w->number("gamma", 7.0, Range::positive());
    sim.water.flip = w->number("flip", 0.0, Range::between(0.0, 1.0));
    if (w->has("hydrostatic_surface")) sc.hydrostatic_surface = w->quantity("hydrostatic_surface", "m");
    sc.water_regions = read_regions(*w, Dim, lo[1]);
    for (const auto& r : sc.water_regions) check_inside<Dim>(*w, r, sim.walls.lo, sim.walls.hi, "water");
  }
  if (const auto s = root.optional_section("soil")) {
    sim.soil.flip = s->number("flip", 0.0, Range::between(0.0, 1.0));
    sim.soil.density = s->quantity("density", "kg/m^3", Range::positive());
    const double young = s->quantity("young", "Pa", Range::positive());
    const double poisson = s->number("poisson", 0.3, Range{-1.0, 0.5, true, true});
    const double phi = s->quantity("friction_angle", "rad", Range::between(0.0, 1.4));
    // The cohesion in Pa, or the dissertation's dimensionless strain-space c_C mapped to Pa
    // (materials/hencky_drucker_prager.hpp, cohesion_of_strain_shift).
    const bool shift = s->has("cohesion_shift");
    if (shift && s->has("cohesion"))
      s->reject("cohesion_shift", "give cohesion (Pa) or cohesion_shift (the dimensionless c_C), not both");
    const double c0 = shift ? 0.0 : s->quantity("cohesion", "Pa", 0.0, Range::at_least(0));
    sim.soil.material = HenckyDruckerPrager::from_young(young, poisson, phi, c0, s->get<bool>("volume_correction", true));
    if (shift) {
      const double c_C = s->number("cohesion_shift", Range::at_least(0));
      if (!(phi > 0)) s->reject("cohesion_shift", "needs a friction_angle > 0 (the strain-space cone's slope)");
      sim.soil.material.cohesion =
          cohesion_of_strain_shift(c_C, sim.soil.material.template bulk_modulus<Dim>(), phi);
    }
    if (const auto mu_i = s->optional_section("inertial_friction")) {
      const double phi_2 = mu_i->quantity("friction_angle_2", "rad", Range::between(0.0, 1.5));
      if (!(phi_2 > phi)) mu_i->reject("friction_angle_2", "must be larger than soil.friction_angle");
      sim.soil.material.set_inertial_friction(phi_2, mu_i->number("inertial_number_0", Range::positive()),
                                              mu_i->quantity("grain_diameter", "m", Range::positive()),
                                              mu_i->quantity("grain_density", "kg/m^3", Range::positive()));
    }
    read_erosion(*s, sim.erosion);
    sim.soil.porosity = s->number("porosity", 0.4, Range{0.0, 1.0, true, true});
    sim.soil.conductivity = s->quantity("conductivity", "m/s", 1e-4, Range::positive());
    sc.soil_regions = read_regions(*s, Dim, lo[1], true, root.has("water"));
    for (const auto& r : sc.soil_regions) {
      check_inside<Dim>(*s, r, sim.walls.lo, sim.walls.hi, "soil");
      sim.loads = sim.loads || r.surcharge > 0;
    }
    sim.load_ramp = s->quantity("surcharge_ramp", "s", 0.0, Range::at_least(0));
  }
  // The water's friction on its beds (erosion/bed_shear.hpp), which the excess-stress erosion needs.
  if (const auto bed = root.optional_section("bed_shear"))
    sim.bed_shear.manning_n = bed->number("manning_n", Range::positive());  // s/m^(1/3), SI
  if (sim.erosion.on && !sim.bed_shear.on())
    root.section("soil").reject("erosion", "the excess-stress erosion needs the flow's shear on the bed: add "
                                           "bed_shear: {manning_n: N} (e.g. 0.016 for bare soil)");
  if (const auto inlet = root.optional_section("inlet")) {
    if (!root.has("water")) root.reject("inlet", "an inlet needs the water: section (density, bulk_modulus, regions)");
    sim.inlet = read_inlet<Dim>(*inlet, sim.walls.lo, sim.walls.hi, sim.h / sc.particles_per_cell, sim.water.density);
  }
  const auto initial = root.section_or_empty("initial_state");
  sc.initial.geostatic = initial.get<bool>("geostatic", true);
  sc.initial.hydrostatic = initial.get<bool>("hydrostatic", true);
  if (initial.has("k0")) sc.initial.k0 = initial.number("k0", Range::positive());
  if (sc.hydrostatic_surface && initial.has("hydrostatic") && !sc.initial.hydrostatic)
    initial.reject("hydrostatic", "the scene gives water.hydrostatic_surface; drop one of the two");
  if (sc.water_regions.empty() && sc.soil_regions.empty() && !sim.inlet)
    root.reject("water", "the scene has no material: give water: {regions: ...} or soil: {regions: ...}");

  // Buoyancy needs both species; a scene with one does not pay for it.
  sim.buoyancy = root.get<bool>("buoyancy", true) && root.has("water") && root.has("soil");
  sim.mixture = root.get<bool>("mixture", false);
  if (sim.mixture && !sim.buoyancy && root.has("water") && root.has("soil"))
    root.reject("mixture", "the mixture's pore pressure acts on the skeleton through the buoyancy; drop buoyancy: false "
                           "or mixture: true");
  // The free water on a field of its own, in contact with the soil (coupling/free_water.hpp).
  sim.free_water_field = root.get<bool>("free_water_field", false);
  if (sim.free_water_field && sim.mixture)
    root.reject("free_water_field",
                "the mixture's pore water shares its field with the free water; drop mixture: true "
                "or free_water_field: true");
  const auto drag = root.choice("drag", {"lumped", "consistent", "explicit"}, "lumped");
  sim.drag = drag == "lumped" ? DragScheme::lumped : drag == "consistent" ? DragScheme::consistent
                                                                          : DragScheme::explicit_euler;
  // The elastic forces at the step's start or its end (model/implicit_forces.cpp).
  const auto forces = root.choice("forces", {"explicit", "implicit"}, "explicit");
  if (forces == "implicit") {
    sim.forces = ForceScheme::implicit_end;
    if (sim.drag != DragScheme::lumped)
      root.reject("forces", fmt::format("the implicit forces couple the species with the lumped drag, and this scene's "
                                        "drag is {}; set drag: lumped or forces: explicit",
                                        drag));
    if (sim.mixture) root.reject("forces", "the implicit forces do not include the mixture; drop mixture: true or set "
                                           "forces: explicit");
    if (sim.free_water_field)
      root.reject("forces",
                  "the implicit forces do not include the free water's own field; drop free_water_field: "
                  "true or set forces: explicit");
    const auto implicit = root.section_or_empty("implicit");
    sim.clamp_passes = static_cast<int>(implicit.integer("clamp_passes", 1, 1, 100));
    sim.plastic_solve = implicit.choice("plasticity", {"in_solve", "after_solve"}, "in_solve") == "in_solve";
  } else if (root.has("implicit")) {
    root.reject("implicit", "the implicit: section sets the implicit forces' solve; add forces: implicit or drop it");
  }
  sc.petsc_options = root.get<std::string>("petsc_options", "");
  if (!sc.petsc_options.empty() && sim.drag != DragScheme::consistent && forces != "implicit")
    root.reject("petsc_options", fmt::format("only the consistent drag and the implicit forces solve with PETSc, and this "
                                             "scene has drag: {} and forces: explicit; set drag: consistent or forces: "
                                             "implicit, or drop petsc_options",
                                             drag));
  const auto time = root.section("time");
  sc.time.end = time.quantity("end", "s", Range::positive());
  sim.cfl = time.number("cfl", 0.4, Range{0.0, 1.0, true, true});
  sim.dt_max = time.quantity("dt_max", "s", 1e-3, Range::positive());
  sc.time.series = time.quantity("series", "s", sc.time.end / 100, Range::positive());
  sc.time.output = time.quantity("output", "s", sc.time.end / 10, Range::positive());
  sc.time.max_steps = time.integer("max_steps", 0, 0, std::numeric_limits<long long>::max());
  // Over several ranks: how often the load is measured, and the imbalance that repartitions.
  const auto dd = root.section_or_empty("decomposition");
  sim.decomposition.check_every = static_cast<int>(dd.integer("check_every", 20, 0, 1000000));
  sim.decomposition.imbalance = dd.number("imbalance", 1.05, Range::at_least(1));
  sim.decomposition.diffuse = dd.choice("repartition", {"diffuse", "fresh"}, "diffuse") == "diffuse";
  // Read only with the consistent drag, so that other scenes' effective_config.yaml lacks them.
  if (sim.drag == DragScheme::consistent) {
    const std::string rows = dd.choice("drag_rows", {"auto", "owners", "balanced"}, "auto");
    sim.drag_rows = rows == "owners" ? DragRows::owners : rows == "balanced" ? DragRows::balanced : DragRows::automatic;
    sim.decomposition.balance_wet_soil = dd.get<bool>("balance_wet_soil", true);
  } else {
    for (const char* key : {"drag_rows", "balance_wet_soil"})
      if (dd.has(key))
        dd.reject(key, fmt::format("only the consistent drag has a distributed solve, and this scene has drag: {}; "
                                   "set drag: consistent or drop decomposition.{}",
                                   drag, key));
  }
  sc.checkpoints = checkpoint::ScheduleSettings::read(root.section_or_empty("checkpoint"), {1000, 1800.0, 2});
  cfg.finish();
  return sc;
}

template <int Dim>
Seeded seeded_at(const Scene<Dim>& sc, const Vec<Dim>& x) {
  Seeded seeded;
  for (const auto& r : sc.soil_regions)
    if (r.template contains<Dim>(x)) seeded.soil = true, seeded.water = seeded.water || r.saturated;
  if (!seeded.soil)
    for (const auto& r : sc.water_regions) seeded.water = seeded.water || r.template contains<Dim>(x);
  return seeded;
}

template <int Dim>
void seed_particles(const Scene<Dim>& sc, Simulation<Dim>& sim, const mpi::Comm* comm) {
  const auto& s = sc.simulation;
  const int ppc = sc.particles_per_cell;
  const double spacing = s.h / ppc, volume = std::pow(spacing, Dim);
  Index<Dim> count;
  for (int d = 0; d < Dim; ++d) count[d] = static_cast<int>(std::llround((s.walls.hi[d] - s.walls.lo[d]) / spacing));
  // The lattice in layers across its last axis (y in 2D, z in 3D), the slowest in its numbering.
  const long long layers = count[Dim - 1];
  long long per_layer = 1;
  for (int d = 0; d + 1 < Dim; ++d) per_layer *= count[d];
  // f(x, soil, water) for the lattice points of layers [first, last) in numbering order (x
  // fastest), with the particles each one gets: a soil particle, a water particle (a soil
  // point's pore water where its region is saturated), both or none.
  auto walk = [&](long long first, long long last, auto&& f) {
    for (long long n = first * per_layer; n < last * per_layer; ++n) {
      long long r = n;
      Vec<Dim> x;
      for (int d = 0; d < Dim; ++d) {
        x[d] = s.walls.lo[d] + (static_cast<double>(r % count[d]) + 0.5) * spacing;
        r /= count[d];
      }
      const Seeded at = seeded_at(sc, x);
      if (at.soil || at.water) f(x, at.soil, at.water);
    }
  };

  // Over several ranks each seeds a band of whole layers holding about its share of the
  // particles, so that no rank holds the whole scene before the first partition. The bands follow
  // the numbering, so the particles get the numbers (ids) one rank would give them.
  long long first = 0, last = layers;
  std::int64_t water_before = 0, soil_before = 0, water_total = -1, soil_total = -1;
  if (comm && comm->size() > 1) {
    const int parts = comm->size(), part = comm->rank();
    std::vector<double> counts(2 * static_cast<std::size_t>(layers), 0.0);  // soil, water per layer
    for (long long k = part * layers / parts; k < (part + 1) * layers / parts; ++k)
      walk(k, k + 1, [&](const Vec<Dim>&, bool soil, bool water) {
        counts[2 * static_cast<std::size_t>(k)] += soil;
        counts[2 * static_cast<std::size_t>(k) + 1] += water;
      });
    comm->all_reduce(counts, mpi::Comm::Reduction::sum);
    // Rank r's band starts at the first layer with at least r / parts of the particles below it.
    std::vector<long long> below(static_cast<std::size_t>(layers) + 1, 0);
    for (long long k = 0; k < layers; ++k) {
      const auto i = static_cast<std::size_t>(k);
      below[i + 1] = below[i] + std::llround(counts[2 * i] + counts[2 * i + 1]);
    }
    const auto band_start = [&](int r) {
      return static_cast<long long>(
          std::lower_bound(below.begin(), below.end() - 1, (below.back() * r + parts - 1) / parts) - below.begin());
    };
    first = band_start(part);
    last = part + 1 == parts ? layers : band_start(part + 1);
    soil_total = water_total = 0;
    for (long long k = 0; k < layers; ++k) {
      const auto soil = std::llround(counts[2 * static_cast<std::size_t>(k)]);
      const auto water = std::llround(counts[2 * static_cast<std::size_t>(k) + 1]);
      if (k < first) soil_before += soil, water_before += water;
      soil_total += soil, water_total += water;
    }
  }

  // The surcharge on a soil particle: that of each region whose upper surface it is on.
  auto load = [&](const Vec<Dim>& x) {
    Vec<Dim> above = x, f = Vec<Dim>::Zero();
    above[1] += spacing;
    for (const auto& r : sc.soil_regions)
      if (r.surcharge > 0 && r.template contains<Dim>(x) && !r.template contains<Dim>(above))
        f[1] -= r.surcharge * std::pow(spacing, Dim - 1);
    return f;
  };
  // The particles at rest in the scene's initial state: water filling the part `fraction` of its
  // lattice cell at the hydrostatic J (volume0 = fraction volume / J), soil at its geostatic F_E
  // (volume0 = volume / det F_E).
  const InitialState<Dim> initial(sc, spacing);
  auto add_water = [&](const Vec<Dim>& x, double fraction, double pressure) {
    const double J = initial.water_j(pressure);
    sim.water().add(x, Vec<Dim>::Zero(), s.water.density * fraction * volume, fraction * volume / J);
    sim.water().J.back() = J;
  };
  auto add_soil = [&](const Vec<Dim>& x, const InitialPoint& at, bool wet) {
    const Mat<Dim> F = initial.soil_gradient(at.vertical_effective, wet ? 1.0 : 0.0);
    sim.soil().add(x, Vec<Dim>::Zero(), s.soil.density * volume, volume / F.determinant());
    sim.soil().F.back() = F;
    if (s.loads) sim.soil().load.back() = load(x);
  };
  // Pore water: a whole water particle, or in the mixture the pores' part n.
  const double pores = s.mixture ? s.soil.porosity : 1.0;
  const std::int64_t water_base = sim.water().next_id, soil_base = sim.soil().next_id;
  sim.water().next_id = water_base + water_before;
  sim.soil().next_id = soil_base + soil_before;
  walk(first, last, [&](const Vec<Dim>& x, bool soil, bool water) {
    const InitialPoint at = initial.at(x, {soil, water});
    if (soil) add_soil(x, at, water);
    if (water) add_water(x, soil ? pores : 1.0, at.pressure);
  });
  // Every rank numbers on after the whole scene's particles (rank 0's inlet goes on from there).
  if (water_total >= 0) sim.water().next_id = water_base + water_total;
  if (soil_total >= 0) sim.soil().next_id = soil_base + soil_total;
}

template bool Region::contains<2>(const Vec<2>&, double) const;
template bool Region::contains<3>(const Vec<3>&, double) const;
template struct Scene<2>;
template struct Scene<3>;
template Scene<2> read_scene<2>(const config::Config&);
template Scene<3> read_scene<3>(const config::Config&);
template Seeded seeded_at<2>(const Scene<2>&, const Vec<2>&);
template Seeded seeded_at<3>(const Scene<3>&, const Vec<3>&);
template void seed_particles<2>(const Scene<2>&, Simulation<2>&, const mpi::Comm*);
template void seed_particles<3>(const Scene<3>&, Simulation<3>&, const mpi::Comm*);

}  // namespace suite::mpm2grid
