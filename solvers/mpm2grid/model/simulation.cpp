#include "solvers/mpm2grid/model/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "solvers/mpm2grid/coupling/free_water.hpp"
#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/kernels/vector_clones.hpp"
#include "solvers/mpm2grid/materials/drucker_prager_return.hpp"
#include "solvers/mpm2grid/model/trial_deformation.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"
#include "solvers/mpm2grid/transfer/particle_order.hpp"
#include "solvers/mpm2grid/transfer/stencil_rows.hpp"

namespace suite::mpm2grid {

template <int Dim>
Simulation<Dim>::Simulation(const SimulationSettings<Dim>& settings, std::optional<mpi::Comm> comm)
    : s_(settings),
      grid_(settings.h),
      water_walls_(settings.walls.for_water()),
      fold_(settings.walls, grid_.spacing(), settings.inlet.has_value()),
      water_fold_(water_walls_, grid_.spacing(), settings.inlet.has_value()),
      shape_fold_(settings.walls.all_slip(), grid_.spacing(), false),
      comm_(std::move(comm)) {
  if (s_.threads < 1) throw std::invalid_argument("threads per rank: give 1 or more");
  grid_.set_walls_box(s_.walls.lo, s_.walls.hi);  // the blocks' indices in an array over the walls' box
  if (s_.inlet) inlet_.emplace(*s_.inlet);
  if (comm_ && comm_->size() > 1) dd_.emplace(*comm_, s_.decomposition, grid_);
  if (s_.erosion.on && !s_.bed_shear.on())
    throw std::invalid_argument("the excess-stress erosion needs the bed shear (a Manning n > 0)");
  if (s_.free_water_field && (s_.mixture || s_.forces == ForceScheme::implicit_end))
    throw std::invalid_argument("the free water's own field works without the mixture and with the explicit forces");
  if (s_.bed_shear.on())
    bed_shear_.emplace(s_.walls, s_.h, s_.water.density, s_.soil.density, s_.bed_shear, s_.erosion, s_.gravity);
  if (s_.forces == ForceScheme::implicit_end) {
    if (!comm_) throw std::invalid_argument("the implicit forces' Newton-Krylov solve needs a communicator");
    if (s_.drag != DragScheme::lumped || s_.mixture)
      throw std::invalid_argument("the implicit forces work with the lumped drag and without the mixture");
    // The residual is in m/s: 1e-9 m/s RMS, or 1e-4 of the explicit guess's residual (the
    // difference between the explicit and the implicit update), each GMRES solve to 1e-2. Against
    // 1e-6 and 1e-3: 37% fewer residual evaluations on example 2 (34 -> 21 a step at 0.5 m), 35%
    // on the water column, with the same eroded volume, outflow and fronts to 5 digits.
    newton_ = std::make_unique<NewtonKrylov>(
        *comm_, NewtonKrylovSettings{.prefix = "implicit_", .atol_per_entry = 1e-9, .rtol = 1e-4, .krylov_rtol = 1e-2});
  }
  if (s_.drag != DragScheme::consistent) return;
  if (!comm_) throw std::invalid_argument("the consistent drag solve needs a communicator");
  consistent_ = std::make_unique<ConsistentDrag<Dim>>(*comm_, "drag_", s_.drag_rows);
}

template <int Dim>
StepLimit Simulation<Dim>::stable_dt(const std::optional<ParticleExtremes>& known) const {
  ParticleExtremes e;
  if (known) {
    e = *known;
  } else {
    double vmax2 = 0;  // the largest |v|^2: one square root, not one per particle (the same max)
    for (const auto* P : {&water_, &soil_})
      for (const auto& v : P->v) vmax2 = std::max(vmax2, v.squaredNorm());
    // One reduction: the fastest particle and whether each species has particles on some rank.
    std::array<double, 3> most{std::sqrt(vmax2), water_.size() > 0 ? 1.0 : 0.0, soil_.size() > 0 ? 1.0 : 0.0};
    max_over_ranks(most);
    e = {most[0], most[1] > 0, most[2] > 0};
  }
  const double vmax = e.fastest;
  const bool water = e.water, soil = e.soil;
  const double h = grid_.spacing();
  StepLimit best{s_.dt_max, "dt_max"};
  auto consider = [&](double dt, const char* why) {
    if (dt < best.dt) best = {dt, why};
  };
  if (vmax > 0) consider(s_.cfl * h / vmax, "cfl (velocity)");
  if (s_.forces == ForceScheme::implicit_end) return best;  // no wave limits the implicit forces
  if (water) {
    double c = s_.water.eos.sound_speed(s_.water.density);
    // The wave in the pores also moves the skeleton (docs/methods/mpm2grid.md, "Mixture (optional)").
    if (s_.mixture && soil) {
      const double n = s_.soil.porosity;
      c *= std::sqrt(1 + s_.water.density * (1 - n) * (1 - n) / (n * s_.soil.density));
    }
    consider(s_.cfl * h / c, "water wave speed");
  }
  if (soil) consider(s_.cfl * h / s_.soil.material.p_wave_speed(s_.soil.density), "soil elastic wave speed");
  return best;
}

template <int Dim>
void Simulation<Dim>::build_grid() {
  std::optional<StepPhaseScope> timed(std::in_place, times_, StepPhase::grid, wait_clock());
  grid_.clear();
  // Each species' particles are put back in group order where they drifted from it (the
  // transfers' speed; transfer/particle_order.hpp), the soil's known stresses with them.
  // The groups stay with their particles: P2G's schedules are cut from them. With threads, the
  // groups go colour by colour, as P2G's schedule sweeps them (transfer/sweep_schedule.hpp).
  // (Both species touch first: the colour ranks then cover every block. Reordering the water
  // after the soil's touch gives the same order, the water's groups keeping their indices.)
  water_schedule_.reset(), soil_schedule_.reset();
  const int threads = s_.threads;
  touch(water_, water_schedule_.groups());
  touch(soil_, soil_schedule_.groups());
  const std::vector<int>* rank = threads > 1 ? &colour_rank_ : nullptr;
  if (rank) colour_ranks(grid_, colour_rank_);
  const auto reorder = [&](Particles<Dim>& P, std::vector<int>& groups, auto&... along) {
    const auto order = group_order(groups, grid_.blocks(), threads, rank);
    if (order.empty()) return;
    P.for_each_array([&](auto& values) { apply_order(values, order, threads); });
    apply_order(groups, order, threads);
    (apply_order(along, order, threads), ...);
  };
  reorder(water_, water_schedule_.groups());
  size_stresses();
  reorder(soil_, soil_schedule_.groups(), soil_tau_, stress_known_);
  if (dd_) {
    timed.emplace(times_, StepPhase::halo_plan, wait_clock());
    dd_->prepare(grid_);  // adds the halo blocks after these
    timed.emplace(times_, StepPhase::grid, wait_clock());
  }
  water_nodes_.reset(grid_.nodes(), s_.threads);
  soil_nodes_.reset(grid_.nodes(), s_.threads);
  if (s_.free_water_field) free_nodes_.reset(grid_.nodes(), s_.threads);
}

// With the free-water field: the soil's shape on the grid (complete on owned nodes, its fill on
// ghost nodes too) and which water particles are free (coupling/free_water.hpp).
template <int Dim>
void Simulation<Dim>::sort_water() {
  {
    auto timed = phase(StepPhase::p2g_soil);
    shape_nodes_.reset(grid_.nodes(), s_.threads);
    if (s_.threads == 1)
      spread_soil_shape(soil_, grid_, shape_fold_, shape_nodes_);
    else  // by colours, as the soil's P2G
      for (const SweepParts& parts : soil_schedule_.colours(grid_, {}, s_.threads))
        in_parts(parts, [&](std::size_t, std::span<const ParticleRun> runs) {
          spread_soil_shape(soil_, grid_, shape_fold_, shape_nodes_, runs);
        });
  }
  if (dd_) {
    auto timed = phase(StepPhase::halo_sum);
    dd_->sum_to_owners(shape_nodes_);
  }
  const double per_kg = 1 / (s_.soil.density * std::pow(grid_.spacing(), Dim));
  const std::size_t nodes = grid_.nodes();
  soil_fill_.resize(nodes);
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
  for (std::size_t i = 0; i < nodes; ++i) soil_fill_[i] = per_kg * shape_nodes_.mass[i];
  if (dd_) {
    auto timed = phase(StepPhase::halo_copy);
    dd_->copy_to_ghosts(soil_fill_);
  }
  auto timed = phase(StepPhase::p2g_water);
  free_water_.resize(water_.size());
  for_parts(water_.size(),
            [&](ParticleRun run) { sort_free_water(water_, grid_, soil_fill_, shape_fold_, free_water_, run); });
}

// The transfers and touch_blocks are compiled for the baseline and for AVX2
// (kernels/vector_clones.hpp): there std::floor is one instruction. With threads, touch_blocks'
// three passes (transfer/apic.hpp, blocks_reached).
template <int Dim>
void Simulation<Dim>::touch(const Particles<Dim>& P, std::vector<int>& groups) {
  if (s_.threads == 1) return touch_part(P, groups, {});
  groups.resize(P.size());
  cut_evenly(P.size(), parts_);
  reached_.resize(parts_.size());
  in_parts(parts_, [&](std::size_t k, std::span<const ParticleRun> runs) { touch_part(P, reached_[k], runs[0]); });
  for (std::size_t k = 0; k < parts_.size(); ++k)
    for (const Index<Dim>& b : reached_[k]) grid_.activate(b);
  in_parts(parts_, [&](std::size_t, std::span<const ParticleRun> runs) { touch_part(P, groups, runs[0]); });
}

// One part of touch(): without `run`, touch_blocks; with it, the blocks the run's stencils reach
// (into `reached`) or, the blocks active, the run's groups (into `groups`).
template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::touch_part(const Particles<Dim>& P, std::vector<int>& groups,
                                                     std::optional<ParticleRun> run) {
  if (!run) return touch_blocks(P, grid_, &groups);
  find_groups(P, grid_, *run, groups);
}
template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::touch_part(const Particles<Dim>& P, std::vector<Index<Dim>>& reached,
                                                     ParticleRun run) {
  blocks_reached<Dim>(P, run, grid_.spacing(), reached);
}

// The particles' stress inputs to P2G: the water's pressures (its Kirchhoff stress is -J p I),
// the soil's Kirchhoff stresses, drag coefficients c_E V_p and solid volumes (1 - n) V_p.
template <int Dim>
void Simulation<Dim>::stresses() {
  water_pressure_.resize(water_.size());
  const std::size_t n_water = water_.size(), n_soil = soil_.size();
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
  for (std::size_t p = 0; p < n_water; ++p) water_pressure_[p] = s_.water.eos.pressure(water_.J[p]);
  soil_drag_.resize(soil_.size());
  solid_volume_.resize(s_.buoyancy ? soil_.size() : 0);
  const double c_e = s_.soil.drag_coefficient(s_.water.density), solid = 1 - s_.soil.porosity;
  const bool implicit = s_.forces == ForceScheme::implicit_end;
#pragma omp parallel for schedule(dynamic, kPart) num_threads(s_.threads) if (s_.threads > 1)
  for (std::size_t p = 0; p < n_soil; ++p) {
    // (The implicit forces take the stress at the step's end: none is needed here.)
    if (!implicit && !stress_known_[p]) soil_tau_[p] = s_.soil.material.template kirchhoff<Dim>(soil_.F[p]);
    const double volume = soil_.volume0[p] * soil_.F[p].determinant();
    soil_drag_[p] = c_e * volume;
    if (s_.buoyancy) solid_volume_[p] = solid * volume;
  }
}

template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::spread_part(const Particles<Dim>& P, const P2GSources<Dim>& in,
                                                      NodeFields<Dim>& nodes) {
  particles_to_grid(P, in, grid_, nodes);
}

// With threads, the groups of one colour at once, colour after colour (transfer/sweep_schedule.hpp).
// (The parallel regions stay out of the vector clones: GCC compiles a region's body as a function
// of its own, for the baseline only; each part calls the clone.)
template <int Dim>
void Simulation<Dim>::spread(const Particles<Dim>& P, ColourSchedule<Dim>& schedule, const P2GSources<Dim>& in,
                             NodeFields<Dim>& nodes) {
  if (s_.threads == 1) return spread_part(P, in, nodes);
  for (const SweepParts& parts : schedule.colours(grid_, in.subset, s_.threads))
    in_parts(parts, [&](std::size_t, std::span<const ParticleRun> runs) {
      P2GSources<Dim> part = in;
      part.runs = runs;
      spread_part(P, part, nodes);
    });
}

template <int Dim>
template <class F>
void Simulation<Dim>::in_parts(const SweepParts& parts, F&& f) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(s_.threads)
  for (std::size_t k = 0; k < parts.size(); ++k) f(k, parts[k]);
}

template <int Dim>
template <class F>
void Simulation<Dim>::for_parts(std::size_t particles, F&& f) {
  if (s_.threads == 1) return f(ParticleRun{0, particles});
  cut_evenly(particles, parts_);
  in_parts(parts_, [&](std::size_t, std::span<const ParticleRun> runs) { f(runs[0]); });
}

// P2G of both species. The water goes first: its node pressures p_i = sum_p w_ip m_p p_p / m_i
// (0 where there is no water), complete on every active node after the halo sum and copy, give
// the buoyancy on the soil in the soil's P2G (docs/methods/mpm2grid.md, "Buoyancy"). With the lumped or consistent
// drag, the forces go into the momentum sums times dt (P2GSources::fold_dt); the explicit drag
// needs the momentum alone. Every rank of a decomposition takes part (the halo exchanges), with
// or without particles.
template <int Dim>
void Simulation<Dim>::particles_to_grids(double dt) {
  const double fold_dt = s_.drag == DragScheme::explicit_euler ? 0.0 : dt;
  // The implicit forces leave the stresses out here (model/implicit_forces.cpp adds them).
  const bool implicit = s_.forces == ForceScheme::implicit_end;
  // With a FLIP share the same sweep spreads the mass and momentum before the forces.
  NodeFields<Dim>* water_before = s_.water.flip > 0 ? &water_before_ : nullptr;
  NodeFields<Dim>* soil_before = s_.soil.flip > 0 ? &soil_before_ : nullptr;
  const bool free = s_.free_water_field;
  NodeFields<Dim>* free_before = free && s_.water.flip > 0 ? &free_before_ : nullptr;
  for (NodeFields<Dim>* before : {water_before, soil_before, free_before})
    if (before) before->reset(grid_.nodes(), s_.threads);
  {
    auto timed = phase(StepPhase::p2g_water);
    // With the free-water field the pore water's particles to water_nodes_, the free ones to
    // free_nodes_.
    P2GSources<Dim> water{.pressure = &water_pressure_,
                          .pressure_force = !implicit,
                          .fold_dt = fold_dt,
                          .walls = &water_fold_,
                          .gravity = s_.gravity,
                          .before = water_before};
    if (free) water.subset = {&free_water_, 0};
    spread(water_, water_schedule_, water, water_nodes_);
    if (free) {
      water.before = free_before, water.subset = {&free_water_, 1};
      spread(water_, water_schedule_, water, free_nodes_);
    }
  }
  if (dd_) {
    auto timed = phase(StepPhase::halo_sum);
    dd_->sum_to_owners(water_nodes_);
    if (water_before) dd_->sum_to_owners(*water_before);
    if (free) dd_->sum_to_owners(free_nodes_);
    if (free_before) dd_->sum_to_owners(*free_before);
  }
  P2GSources<Dim> soil{.tau = implicit ? nullptr : &soil_tau_,
                       .drag = &soil_drag_,
                       .fold_dt = fold_dt,
                       .walls = &fold_,
                       .gravity = s_.gravity,
                       .before = soil_before};
  if (s_.buoyancy) {
    // The node pressures of all the water, free and pore.
    auto& p = water_nodes_.pressure;
    const std::size_t n = grid_.nodes();
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
    for (std::size_t i = 0; i < n; ++i) {
      const double m = water_nodes_.mass[i] + (free ? free_nodes_.mass[i] : 0.0);
      p[i] = m > 0 ? (p[i] + (free ? free_nodes_.pressure[i] : 0.0)) / m : 0.0;
    }
    if (dd_) {
      auto timed = phase(StepPhase::halo_sum);
      dd_->copy_to_ghosts(p);
    }
    soil.solid_volume = &solid_volume_;
    soil.node_pressure = &p;
  }
  {
    auto timed = phase(StepPhase::p2g_soil);
    spread(soil_, soil_schedule_, soil, soil_nodes_);
    if (s_.loads) add_loads();
  }
  if (dd_) {
    auto timed = phase(StepPhase::halo_sum);
    dd_->sum_to_owners(soil_nodes_);
    if (soil_before) dd_->sum_to_owners(*soil_before);
  }
  if (water_before) velocities_before(StepPhase::p2g_water, *water_before);
  if (free_before) velocities_before(StepPhase::p2g_water, *free_before);
  if (soil_before) velocities_before(StepPhase::p2g_soil, *soil_before);
}

template <int Dim>
void Simulation<Dim>::step(double dt) {
  if (dd_) {
    auto timed = phase(StepPhase::balance);
    if (dd_->balance(steps_, water_, soil_)) keep_known_stresses();
  }
  const auto bed_shear = [&](const std::vector<char>* free) {
    if (!bed_shear_) return;
    auto timed = phase(StepPhase::bed_shear);
    bed_shear_->measure(water_, soil_, dd_ ? &dd_->comm() : nullptr, free);
    detached_.clear();
    outflow_.law_eroded_volume += bed_shear_->erode(soil_, dt, &detached_);
    for (const std::size_t p : detached_)  // their F_E is now I
      if (p < stress_known_.size()) stress_known_[p] = 0;
  };
  if (!s_.free_water_field) bed_shear(nullptr);
  build_grid();
  // With the free-water field its sort comes before the bed shear, where a column's flow is its
  // free water (the erosion leaves the soil's masses and positions, which the sort reads, as they
  // are).
  if (s_.free_water_field) sort_water(), bed_shear(&free_water_);
  {
    auto timed = phase(StepPhase::stresses);
    stresses();
  }
  particles_to_grids(dt);
  {
    auto timed = phase(StepPhase::grid_solve);
    if (s_.mixture) solid_fractions();
    solve_grid(dt);
  }
  const double t_next = time_ + dt;
  {
    auto timed = phase(StepPhase::boundary);
    water_walls_.apply(grid_, water_nodes_, s_.threads);
    s_.walls.apply(grid_, soil_nodes_, s_.threads);
    if (inlet_) inlet_->impose(grid_, water_nodes_, t_next);
    if (s_.free_water_field) {
      water_walls_.apply(grid_, free_nodes_, s_.threads);
      if (inlet_) inlet_->impose(grid_, free_nodes_, t_next);
    }
  }
  if (dd_) {
    auto timed = phase(StepPhase::halo_copy);
    dd_->copy_to_ghosts(soil_nodes_, water_nodes_);
    if (s_.free_water_field) dd_->copy_to_ghosts(free_nodes_, free_nodes_);  // velocity and mass
  }
  update_particles(dt);
  {
    auto timed = phase(StepPhase::outflow);
    remove_outflow();
  }
  // The inlet's state is the same on every rank; rank 0 adds its particles, migrate() sends them
  // to their owners.
  if (inlet_) {
    auto timed = phase(StepPhase::inlet);
    inlet_->emit(t_next, water_, !dd_ || dd_->comm().is_root());
  }
  if (dd_) {
    auto timed = phase(StepPhase::migrate);
    dd_->migrate(water_, soil_, &left_home_);
    keep_known_stresses();
  }
  time_ = t_next;
  ++steps_;
}

// After a migration: the known stresses of the soil particles that stayed, none for the received.
template <int Dim>
void Simulation<Dim>::keep_known_stresses() {
  dd_->drop_sent(1, soil_tau_);
  dd_->drop_sent(1, stress_known_);
  size_stresses();
}

// An entry per soil particle in soil_tau_ and stress_known_: none known for those that had none.
template <int Dim>
void Simulation<Dim>::size_stresses() {
  soil_tau_.resize(soil_.size());
  stress_known_.resize(soil_.size(), 0);
}

// The drag-coupled grid velocities on this rank's nodes (on ghost nodes too, from partial sums:
// copy_to_ghosts() replaces them with the owners').
template <int Dim>
void Simulation<Dim>::solve_grid(double dt) {
  if (newton_) return solve_grid_implicit(dt);
  if (!consistent_) {
    solve_grid_velocities(soil_nodes_, water_nodes_, dt, s_.drag, s_.threads);
    free_water_velocities(dt);
    return;
  }
  if (!dd_) {
    const auto numbering = NodeNumbering::own_all(*comm_, soil_nodes_, water_nodes_);
    drag_stats_ = consistent_->solve(grid_, soil_, soil_drag_, soil_nodes_, water_nodes_, dt, numbering,
                                     &soil_schedule_.groups());
    free_water_velocities(dt);
    return;
  }
  // Owners number their coupled nodes; the ghost copies learn the owners' numbers.
  auto numbering = NodeNumbering::own_blocks(*comm_, soil_nodes_, water_nodes_, dd_->owned_blocks());
  dd_->copy_to_ghosts(numbering.global);
  drag_stats_ = consistent_->solve(grid_, soil_, soil_drag_, soil_nodes_, water_nodes_, dt, numbering,
                                   &soil_schedule_.groups(), &dd_->waited());
  free_water_velocities(dt);
}

// With the free-water field: its velocities (no drag), then its contact with the mixture.
template <int Dim>
void Simulation<Dim>::free_water_velocities(double dt) {
  if (!s_.free_water_field) return;
  auto& f = free_nodes_;
  const std::size_t nodes = grid_.nodes();
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
  for (std::size_t i = 0; i < nodes; ++i)
    f.velocity[i] = f.mass[i] > 0 ? Vec<Dim>((f.momentum[i] + dt * f.force[i]) / f.mass[i]) : Vec<Dim>::Zero();
  const double free_per_kg = 1 / (s_.water.density * std::pow(grid_.spacing(), Dim));
  free_water_contact(shape_nodes_, soil_fill_, free_per_kg, soil_nodes_, water_nodes_, free_nodes_, s_.threads);
}

// The soil particles' loads on the soil grid, scaled by the ramp at the step's start.
template <int Dim>
void Simulation<Dim>::add_loads() {
  const double ramp = s_.load_ramp > 0 ? std::min(1.0, time_ / s_.load_ramp) : 1.0;
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  std::array<double, BlockGrid<Dim>::kNodes> weights;
  for (std::size_t q = 0; q < soil_.size(); ++q) {
    if (soil_.load[q].isZero(0.0)) continue;
    const Stencil<Dim> st(soil_.x[q], grid_.spacing());
    grid_.stencil_slots(st, slots);
    st.weights(weights);
    for (int n = 0; n < BlockGrid<Dim>::kNodes; ++n) {
      // A node beyond a wall passes its share to its mirror (boundary/wall_fold.hpp), which lies
      // in the same stencil.
      Index<Dim> node = grid_.node_of(slots[n]);
      Vec<Dim> f = weights[n] * ramp * soil_.load[q];
      fold_.redirect(node, f);
      soil_nodes_.force[static_cast<std::size_t>(grid_.slot_of(node))] += f;
    }
  }
}

// The mixture's soil volume fraction per node (docs/methods/mpm2grid.md, "Mixture (optional)"), on owned
// and ghost nodes.
template <int Dim>
void Simulation<Dim>::solid_fractions() {
  constexpr double kMost = 0.95;  // keeps 1 - phi_s away from zero where B-splines overshoot
  const double per_kg = (1 - s_.soil.porosity) / (s_.soil.density * std::pow(grid_.spacing(), Dim));
  solid_fraction_.assign(grid_.nodes(), 0.0);
  for (std::size_t i = 0; i < grid_.nodes(); ++i) {
    if (!(soil_nodes_.mass[i] > 0)) continue;
    const double inside = fold_.inside_fraction(s_.walls, grid_.position(static_cast<long>(i)), grid_.spacing());
    if (inside > 0) solid_fraction_[i] = std::min(kMost, per_kg * soil_nodes_.mass[i] / inside);
  }
  if (dd_) dd_->copy_to_ghosts(solid_fraction_);
}

// The mixture's J update of the water (docs/methods/mpm2grid.md, "Mixture (optional)"), from the grid
// velocities of both species at the particles' positions at the step's start.
template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::mixture_volume_rates(double dt) {
  // Tile fields: 0 phi_s, 1 .. Dim the volume flux phi_s v_s + (1 - phi_s) v_w.
  using Tile = NodeTile<Dim, 1 + Dim>;
  auto tile = std::make_unique<Tile>();
  constexpr auto fields = scalar_and_vector_fields<Dim>();
  const auto enter = [&] {
    tile->zero();
    tile->for_each_node([&](int t, long slot) {
      const auto i = static_cast<std::size_t>(slot);
      const double f = solid_fraction_[i];
      tile->field(0)[t] = f;
      const Vec<Dim> flux = f * soil_nodes_.velocity[i] + (1 - f) * water_nodes_.velocity[i];
      for (int d = 0; d < Dim; ++d) tile->field(1 + d)[t] = flux[d];
    });
    water_fold_.mirror(*tile, fields);
  };
  sweep_groups(
      water_.x, grid_, *tile, enter, [] {},
      [&](std::size_t p, const StencilRows<Dim>& st, int first) {
        const double phi = sample_field<false, kNoAxes>(*tile, 0, st, first).value;
        double div = 0;
        for_each_axis<Dim>(
            [&]<int d>() { div += sample_field<false, only_axis(d)>(*tile, 1 + d, st, first).gradient[d]; });
        water_.J[p] *= 1 + dt * div / (1 - phi);
      });
}

// With a FLIP share: a species' node velocities before the step's forces, from the mass and
// APIC momentum its P2G spread into `before` (summed to the owners), complete on owned and ghost
// nodes.
template <int Dim>
void Simulation<Dim>::velocities_before(StepPhase p2g, NodeFields<Dim>& before) {
  {
    auto timed = phase(p2g);
    const std::size_t n = grid_.nodes();
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
    for (std::size_t i = 0; i < n; ++i)
      before.velocity[i] = before.mass[i] > 0 ? Vec<Dim>(before.momentum[i] / before.mass[i]) : Vec<Dim>(Vec<Dim>::Zero());
  }
  if (dd_) {
    auto timed = phase(StepPhase::halo_copy);
    dd_->copy_to_ghosts(before, before);
  }
}

template <int Dim>
void Simulation<Dim>::distribute() {
  if (dd_) dd_->balance(steps_, water_, soil_, true);
}

// G2P of the water: v_p and C_p, and div v_p for the J update (not with the mixture, whose J
// update samples the grid itself).
template <int Dim>
void Simulation<Dim>::water_velocities() {
  divergence_.resize(s_.mixture ? 0 : water_.size());
  if (s_.threads == 1) return water_velocities_part({});
  cut_evenly(water_.size(), parts_);
  in_parts(parts_, [&](std::size_t, std::span<const ParticleRun> runs) { water_velocities_part(runs); });
}

template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::water_velocities_part(std::span<const ParticleRun> runs) {
  const FlipBlend<Dim> flip{s_.water.flip > 0 ? &water_before_ : nullptr, s_.water.flip};
  if (s_.mixture) {
    grid_to_particles_each<VelocityGradient::none>(
        water_, grid_, water_nodes_, nullptr, nullptr, &water_fold_, [](std::size_t) {}, flip, {}, runs);
    return;
  }
  const auto keep = [&](std::size_t p, double div) { divergence_[p] = div; };
  if (!s_.free_water_field) {
    grid_to_particles_each<VelocityGradient::divergence>(water_, grid_, water_nodes_, nullptr, nullptr, &water_fold_,
                                                         keep, flip, {}, runs);
    return;
  }
  // The pore water from its field, the free water from its own.
  grid_to_particles_each<VelocityGradient::divergence>(water_, grid_, water_nodes_, nullptr, nullptr, &water_fold_,
                                                       keep, flip, {&free_water_, 0}, runs);
  const FlipBlend<Dim> free_flip{s_.water.flip > 0 ? &free_before_ : nullptr, s_.water.flip};
  grid_to_particles_each<VelocityGradient::divergence>(water_, grid_, free_nodes_, nullptr, nullptr, &water_fold_, keep,
                                                       free_flip, {&free_water_, 1}, runs);
}

// probe_.v and probe_.C: the velocity and APIC matrix of `nodes` at the points probe_.x.
template <int Dim>
void Simulation<Dim>::sample(const NodeFields<Dim>& nodes, const WallFold<Dim>& walls) {
  probe_.v.resize(probe_.x.size());
  probe_.C.resize(probe_.x.size());
  grid_to_particles_each<VelocityGradient::none>(probe_, grid_, nodes, nullptr, nullptr, &walls, [](std::size_t) {});
}

// The water grid's masses for the saturation (docs/methods/mpm2grid.md, "Continuum model"), each
// divided by the part of its node's weight inside the walls. Only the blocks within two cells of a
// wall hold nodes with part of their weight outside. Across a wall where the water folds and the
// soil does not (a friction wall), the node beyond it, which the water's fold emptied, reads its
// mirror's fill: the soil's G2P samples it as it is.
template <int Dim>
void Simulation<Dim>::wall_water_fill() {
  water_fill_ = water_nodes_.mass;
  if (s_.free_water_field)
    for (std::size_t i = 0; i < water_fill_.size(); ++i) water_fill_[i] += free_nodes_.mass[i];
  constexpr int kSide = BlockGrid<Dim>::kSide;
  const double h = grid_.spacing(), reach = 2 * h;
  std::vector<std::size_t> near_blocks;
  for (std::size_t b = 0; b < grid_.blocks(); ++b) {
    const Index<Dim>& c = grid_.block_coord(b);
    bool near = false;
    for (int d = 0; d < Dim; ++d)
      near = near || c[d] * kSide * h < s_.walls.lo[d] + reach || (c[d] + 1) * kSide * h > s_.walls.hi[d] - reach;
    if (!near) continue;
    near_blocks.push_back(b);
    for (std::size_t i = b * BlockGrid<Dim>::kNodes; i < (b + 1) * BlockGrid<Dim>::kNodes; ++i) {
      if (!(water_fill_[i] > 0)) continue;
      const double inside = water_fold_.inside_fraction(water_walls_, grid_.position(static_cast<long>(i)), h);
      water_fill_[i] = inside > 0 ? water_fill_[i] / inside : 0.0;
    }
  }
  for (const std::size_t b : near_blocks)
    for (std::size_t i = b * BlockGrid<Dim>::kNodes; i < (b + 1) * BlockGrid<Dim>::kNodes; ++i) {
      const Index<Dim> node = grid_.node_of(static_cast<long>(i));
      Index<Dim> water_mirror = node, soil_mirror = node;
      Vec<Dim> unused = Vec<Dim>::Zero();
      water_fold_.redirect(water_mirror, unused);
      fold_.redirect(soil_mirror, unused);
      if (water_mirror == node || soil_mirror != node) continue;
      if (const long m = grid_.slot_of(water_mirror); m >= 0) water_fill_[i] = water_fill_[static_cast<std::size_t>(m)];
    }
}

// G2P of the soil: v_p, C_p, grad v_p, and the water fill (wall_water_fill()) at the particles.
// The saturation comes from these, sampled at the positions the velocities were spread from:
// the return mapping's cohesion is the step's own.
template <int Dim>
void Simulation<Dim>::soil_velocities() {
  if (s_.threads == 1) {
    soil_velocities_part({});
  } else {
    grad_v_.resize(soil_.size());
    cut_evenly(soil_.size(), parts_);
    in_parts(parts_, [&](std::size_t, std::span<const ParticleRun> runs) { soil_velocities_part(runs); });
  }
  if (s_.erosion.on) carry_suspended();
}

template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::soil_velocities_part(std::span<const ParticleRun> runs) {
  grid_to_particles(soil_, grid_, soil_nodes_, grad_v_, &water_fill_, &soil_.saturation, &fold_,
                    {s_.soil.flip > 0 ? &soil_before_ : nullptr, s_.soil.flip}, runs);
}

// The detached (suspended) soil particles move with the water: v_p and C_p from the water grid.
template <int Dim>
void Simulation<Dim>::carry_suspended() {
  std::vector<std::size_t> carried;
  probe_.x.clear();
  for (std::size_t p = 0; p < soil_.size(); ++p)
    if (bed_shear_->suspended(soil_, p)) carried.push_back(p), probe_.x.push_back(soil_.x[p]);
  if (carried.empty()) return;
  if (!s_.free_water_field) {
    sample(water_nodes_, water_fold_);
    for (std::size_t k = 0; k < carried.size(); ++k)
      soil_.v[carried[k]] = probe_.v[k], soil_.C[carried[k]] = probe_.C[k];
    return;
  }
  // The free water's velocity weighted by its node masses, sum_i w_ip m_i v_i / sum_i w_ip m_i:
  // at the bed the free field's nodes inside the soil hold only its kernel tails, whose velocities
  // (a light node's forces over its mass) carried a grain at 87-261 m/s (example 2 at h = 0.0625
  // m blew up after 5.75 s). C_p = 0: the first moment of the mass-weighted momentum is no affine
  // velocity (a uniform flow over uneven node masses gives C = v (the mass's offset)^T D^-1, which
  // P2G spread back as momentum: a cluster of grains on the dam's face ran away to 58 m/s in 22
  // steps, example 2 at h = 0.0625 m after 6.4 s), and a suspension's grains need none. A grain
  // that no free water reaches moves with the soil's velocity weighted the same way (by the soil's
  // fill, its mass complete on ghost nodes too): with the bed it lies on, not with the bed's light
  // surface nodes (the bed's stresses over a kernel tail's mass), which a plain G2P reads at a
  // grain's place above the bed.
  const auto carry = [&](const std::vector<Vec<Dim>>& velocity, const std::vector<double>& weight,
                         const WallFold<Dim>& walls) {
    carrier_.velocity.resize(grid_.nodes());
    for (std::size_t i = 0; i < grid_.nodes(); ++i) carrier_.velocity[i] = weight[i] * velocity[i];
    probe_.v.resize(probe_.x.size());
    probe_.C.resize(probe_.x.size());
    grid_to_particles_each<VelocityGradient::none>(probe_, grid_, carrier_, &weight, &carried_mass_, &walls,
                                                   [](std::size_t) {});
    std::size_t left = 0;  // the grains this field does not reach, for the next
    for (std::size_t k = 0; k < carried.size(); ++k) {
      if (const double m = carried_mass_[k]; m > 0) {
        soil_.v[carried[k]] = probe_.v[k] / m, soil_.C[carried[k]] = Mat<Dim>::Zero();
      } else {
        carried[left] = carried[k], probe_.x[left] = probe_.x[k];
        ++left;
      }
    }
    carried.resize(left), probe_.x.resize(left);
  };
  carry(free_nodes_.velocity, free_nodes_.mass, water_fold_);
  if (!carried.empty()) carry(soil_nodes_.velocity, soil_fill_, fold_);
}

// A species' home blocks before the move (home_before_), and after it which particles it took to
// another one. Passes of their own: inside the soil's update loop, with the return mapping
// inlined there, they slowed the 2-rank step (docs/mpm2grid.md, "Benchmarks"); and in the vector
// clones std::floor is one instruction.
// With threads, each pass in parts of kPart particles.
template <int Dim>
void Simulation<Dim>::record_homes(const Particles<Dim>& P) {
  home_before_.resize(P.size());
  for_parts(P.size(), [&](ParticleRun run) { record_homes(P, run); });
}
template <int Dim>
void Simulation<Dim>::mark_moved(const Particles<Dim>& P, std::vector<char>& left) {
  left.resize(P.size());
  for_parts(P.size(), [&](ParticleRun run) { mark_moved(P, left, run); });
}
template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::record_homes(const Particles<Dim>& P, ParticleRun run) {
  for (std::size_t p = run.begin; p < run.end; ++p) home_before_[p] = BlockGrid<Dim>::key(grid_.home_block(P.x[p]));
}
template <int Dim>
SUITE_VECTOR_CLONES void Simulation<Dim>::mark_moved(const Particles<Dim>& P, std::vector<char>& left,
                                                     ParticleRun run) const {
  for (std::size_t p = run.begin; p < run.end; ++p)
    left[p] = BlockGrid<Dim>::key(grid_.home_block(P.x[p])) != home_before_[p];
}

// The particle updates after G2P. The soil's, with the return mapping, is compiled for the
// baseline only with the return mapping inlined (kernels/vector_clones.hpp, SUITE_INLINE_CALLS),
// which makes the step faster. (Updating each particle inside the G2P sweep instead, its gradient
// never stored, was slower: the return mapping's call inside the sweep's loop costs more than the
// stored gradient. Both in docs/mpm2grid.md, "Benchmarks".)
template <int Dim>
void Simulation<Dim>::update_particles(double dt) {
  // Over several ranks, which particles the move takes to another home block (left_home_):
  // their home blocks before the move, compared after it.
  for (auto& left : left_home_) left.clear();
  std::optional<StepPhaseScope> timed(std::in_place, times_, StepPhase::g2p_water, wait_clock());
  // The implicit forces' steps are long: exp(dt div v) keeps J > 0 at any dt (the implicit
  // solve takes the same J^; model/implicit_forces.cpp).
  const bool implicit = s_.forces == ForceScheme::implicit_end;
  water_velocities();
  if (bed_shear_) {
    timed.emplace(times_, StepPhase::bed_shear, wait_clock());
    bed_shear_->brake(water_, dt, s_.free_water_field ? &free_water_ : nullptr);
    timed.emplace(times_, StepPhase::g2p_water, wait_clock());
  }
  if (s_.mixture) mixture_volume_rates(dt);  // at the positions the water was spread from
  if (dd_) record_homes(water_);
  const std::size_t n_water = water_.size();
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
  for (std::size_t p = 0; p < n_water; ++p) {
    water_.x[p] += dt * water_.v[p];
    if (!s_.mixture) water_.J[p] *= implicit ? std::exp(dt * divergence_[p]) : 1 + dt * divergence_[p];
    s_.walls.clamp(water_.x[p]);
  }
  if (dd_) mark_moved(water_, left_home_[0]);
  timed.emplace(times_, StepPhase::g2p_soil, wait_clock());
  wall_water_fill();
  soil_velocities();  // leaves the sums sum_i w_ip m_w,i / I_i in `saturation`
  if (dd_) record_homes(soil_);
  // (With threads, parts of kPart particles: whole batches of the return mapping.)
  for_parts(soil_.size(), [&](ParticleRun run) { update_soil(dt, run); });
  if (dd_) mark_moved(soil_, left_home_[1]);
}

// The soil particles of `run` after their G2P: position, F_E through the return mapping, known
// stresses, the detached ones stress-free and sinking.
template <int Dim>
SUITE_INLINE_CALLS void Simulation<Dim>::update_soil(double dt, ParticleRun run) {
  const double full = s_.water.density * std::pow(grid_.spacing(), Dim) * s_.soil.porosity;  // kg in a node's pores
  // With the excess-stress erosion the cohesion does not fall with the saturation; detached
  // (suspended) particles carry no stress and sink through the water.
  const bool weakens = !s_.erosion.on;
  // The return mappings kBatch particles at a time (HenckyDruckerPrager::project_all), the last
  // batch filled up with F = I.
  constexpr int kBatch = 4;
  static_assert(kPart % kBatch == 0, "threads' parts hold whole batches");
  for (std::size_t first = run.begin; first < run.end; first += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, run.end - first));
    Mat<Dim> trial[kBatch];
    double log_jp[kBatch], saturation[kBatch];
    for (int n = 0; n < kBatch; ++n) {
      if (n >= count) {
        trial[n] = Mat<Dim>::Identity(), log_jp[n] = 0, saturation[n] = 0;
        continue;
      }
      const std::size_t p = first + static_cast<std::size_t>(n);
      soil_.saturation[p] = std::clamp(soil_.saturation[p] / full, 0.0, 1.0);
      saturation[n] = weakens ? soil_.saturation[p] : 0.0;
      soil_.x[p] += dt * soil_.v[p];
      trial[n] = trial_deformation(grad_v_[p], soil_.F[p], dt);
      log_jp[n] = soil_.log_jp[p];
    }
    ReturnResult<Dim> r[kBatch];
    s_.soil.material.template project_all<Dim, kBatch>(trial, log_jp, saturation, r, dt);
    for (int n = 0; n < count; ++n) {
      const std::size_t p = first + static_cast<std::size_t>(n);
      soil_.F[p] = r[n].F;
      soil_.log_jp[p] = r[n].log_jp;
      stress_known_[p] = r[n].has_stress;
      if (r[n].has_stress) soil_tau_[p] = r[n].stress;
      if (s_.erosion.on && bed_shear_->suspended(soil_, p)) {
        soil_.F[p] = Mat<Dim>::Identity();
        soil_.log_jp[p] = 0;
        stress_known_[p] = 0;
        bed_shear_->settle(soil_, p, dt);
      }
      s_.walls.clamp(soil_.x[p]);
    }
  }
}

template <int Dim>
void Simulation<Dim>::remove_outflow() {
  if (!s_.walls.any_open()) return;  // a closed box (the same on every rank): nothing leaves
  Outflow<Dim> step;                 // this step's, on this rank
  // Which particles left, found over the threads in parts of kPart particles; recorded in their
  // order and taken out (Particles::remove). The per-particle lists of this step go with them.
  const auto take_out = [&](Particles<Dim>& P, double& species_mass, auto&... along) {
    const std::size_t n = P.size(), pieces = (n + kPart - 1) / kPart;
    left_in_part_.resize(pieces);
#pragma omp parallel for schedule(static) num_threads(s_.threads) if (s_.threads > 1)
    for (std::size_t k = 0; k < pieces; ++k) {
      left_in_part_[k].clear();
      for (std::size_t p = k * kPart; p < std::min(n, (k + 1) * kPart); ++p)
        if (s_.walls.left_through_open_side(P.x[p])) left_in_part_[k].push_back(p);
    }
    left_.clear();
    for (const auto& part : left_in_part_) left_.insert(left_.end(), part.begin(), part.end());
    if (left_.empty()) return;
    for (const std::size_t p : left_) {
      species_mass += P.mass[p];
      step.momentum += P.mass[p] * P.v[p];
      if (&P == &soil_ && s_.erosion.on) step.shear_eroded_volume += bed_shear_->eroded_volume(soil_, p);
    }
    P.remove(left_, along...);
  };
  if (dd_) {
    take_out(water_, step.water_mass, left_home_[0]);
    take_out(soil_, step.soil_mass, left_home_[1], soil_tau_, stress_known_);
  } else {
    take_out(water_, step.water_mass);
    take_out(soil_, step.soil_mass, soil_tau_, stress_known_);
  }
  if (dd_) {  // the record is the same on every rank
    std::array<double, 3 + Dim> all{};
    all[0] = step.water_mass, all[1] = step.soil_mass, all[2] = step.shear_eroded_volume;
    for (int d = 0; d < Dim; ++d) all[3 + d] = step.momentum[d];
    dd_->waited().time([&] { dd_->comm().all_reduce(all, mpi::Comm::Reduction::sum); });
    step.water_mass = all[0], step.soil_mass = all[1], step.shear_eroded_volume = all[2];
    for (int d = 0; d < Dim; ++d) step.momentum[d] = all[3 + d];
  }
  outflow_.water_mass += step.water_mass;
  outflow_.soil_mass += step.soil_mass;
  outflow_.shear_eroded_volume += step.shear_eroded_volume;
  outflow_.momentum += step.momentum;
}

template <int Dim>
double Simulation<Dim>::kinetic_energy() const {
  double e = 0;
  for (const auto* P : {&water_, &soil_})
    for (std::size_t p = 0; p < P->size(); ++p) e += 0.5 * P->mass[p] * P->v[p].squaredNorm();
  return sum_over_ranks(e);
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace suite::mpm2grid
