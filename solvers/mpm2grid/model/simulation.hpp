#pragma once
// One two-species (soil + water) MPM model and its time step: Simulation<Dim> (Dim = 2 or 3) with
// its settings, the outflow record and what limits dt. SI units (m, s, kg, Pa); in 2D masses,
// volumes and energies are per metre of width. step() rebuilds the sparse grid, runs P2G per
// species (water first), the drag-coupled grid solve (coupling/), the wall and inlet conditions
// with the walls' mirror fold (boundary/), G2P with the particle updates, and the outflow and
// inlet particles. Over a communicator of more than one rank each rank steps the particles of
// the grid blocks it owns (decomposition/); members marked COLLECTIVE must then be called on
// every rank, and sums over particles (masses, energies, the outflow) are over all ranks.
// The model and its step: docs/methods/mpm2grid.md, "Continuum model" and "Step n -> n+1".
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "solvers/mpm2grid/boundary/inlet.hpp"
#include "solvers/mpm2grid/boundary/wall_fold.hpp"
#include "solvers/mpm2grid/boundary/walls.hpp"
#include "solvers/mpm2grid/coupling/consistent_drag.hpp"
#include "solvers/mpm2grid/coupling/drag_solve.hpp"
#include "solvers/mpm2grid/decomposition/domain_decomposition.hpp"
#include "solvers/mpm2grid/erosion/bed_shear.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/materials/hencky_drucker_prager.hpp"
#include "solvers/mpm2grid/materials/weakly_compressible_water.hpp"
#include "solvers/mpm2grid/model/implicit_state.hpp"
#include "solvers/mpm2grid/model/step_timers.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"
#include "solvers/mpm2grid/transfer/sweep_schedule.hpp"

namespace suite::mpm2grid {

struct WaterSettings {
  double density = 1000;  // kg/m^3
  WeaklyCompressibleWater eos;
  // The FLIP share of the water's G2P, in [0, 1]: v_p = flip (v_p + the grid's change of velocity
  // at x_p) + (1 - flip) (the grid's new velocity at x_p); 0 is APIC alone. APIC's G2P keeps only
  // the grid's affine part of each particle's velocity every step, so it damps the flow by a share
  // per step, not per second: at a few cells across a flow the results depend on the step count
  // (docs/mpm2grid.md, "Water: FLIP share").
  double flip = 0;
};

struct SoilSettings {
  double density = 2000;       // kg/m^3 of the soil skeleton's particles
  double porosity = 0.4;       // n
  double conductivity = 1e-4;  // hydraulic conductivity k, m/s
  HenckyDruckerPrager material;
  double flip = 0;             // the FLIP share of the soil's G2P (WaterSettings::flip); grad v stays APIC's

  // The drag coefficient c_E = n^2 rho_w g0 / k (kg m^-3 s^-1). g0 is standard gravity, not the
  // scene's: a hydraulic conductivity is measured on Earth (k = kappa rho_w g0 / mu_w), and a
  // scene with another gravity (Table 3.4's 3 m/s^2) keeps its soil's permeability.
  double drag_coefficient(double water_density) const {
    constexpr double g0 = 9.80665;
    return porosity * porosity * water_density * g0 / conductivity;
  }
};

template <int Dim>
struct SimulationSettings {
  double h = 0.01;  // grid spacing, m (the scene's; a Simulation's grid() owns it from then on)
  Vec<Dim> gravity = Vec<Dim>::Zero();
  Walls<Dim> walls;
  WaterSettings water;
  SoilSettings soil;
  DragScheme drag = DragScheme::lumped;
  // With the consistent drag over several ranks: the Krylov solve's rows on the coupled nodes'
  // owners, in equal shares, or either by how even the owners are (coupling/consistent_drag.hpp).
  DragRows drag_rows = DragRows::automatic;
  // implicit_end: the elastic forces at the step's end, solved by Newton-Krylov over the
  // communicator (PETSc options prefix "implicit_"); with the lumped drag, without the mixture.
  ForceScheme forces = ForceScheme::explicit_start;
  // With implicit forces: the most Newton solves a step makes while the water's tension clamp
  // changes sides (model/implicit_forces.cpp). 1: each particle's side of the clamp from the
  // step's start, the clamp alone explicit (the water column's front moved by under 0.1% with 2
  // or 4, at twice and 2.4 times the cost).
  int clamp_passes = 1;
  // With implicit forces: the soil's stress in the solve is that of its trial state returned onto
  // Drucker-Prager (the saturation of the step's start), true; or of the elastic trial state, the
  // projection after the solve (the dissertation's eq. 3.26), false. Elastic in the solve, example
  // 2 at h = 0.5 m eroded 0.06 m^2 in 10 s instead of the explicit forces' 1.0 (docs/mpm2grid.md,
  // "Implicit forces").
  bool plastic_solve = true;
  // The water's friction on its beds and the soil's excess-stress erosion (erosion/bed_shear.hpp);
  // with the erosion the soil keeps its cohesion when wet (its erosion is the closure's).
  BedShearSettings bed_shear;
  ExcessStressSettings erosion;
  double cfl = 0.4;                         // fraction of a cell a particle or a wave may cross per step
  double dt_max = 1e-3;                     // s
  std::optional<InletSettings<Dim>> inlet;  // water inlet on the x_low side, if any
  DecompositionSettings decomposition;      // load checks and rebalancing over several ranks
  bool buoyancy = true;                     // the water's pressure acts on the soil skeleton
  bool mixture = false;                     // the pore water's volume balance counts the soil's
  // The water outside the soil on a grid field of its own, met by the soil in a no-penetration
  // contact; the drag acts on the pore water alone (coupling/free_water.hpp). Not with the
  // mixture or the implicit forces.
  bool free_water_field = false;
  // OpenMP threads per rank for the transfers, stresses and particle updates (transfer/
  // sweep_schedule.hpp); 1: none. More than one gives the same results whatever their number, and
  // results that differ from one thread's at round-off (P2G's sums in another order).
  int threads = 1;
  bool loads = false;                       // some soil particles carry loads
  double load_ramp = 0;                     // s over which the loads grow to full (0: at once)
};

// What limits the time step, for the log.
struct StepLimit {
  double dt = 0;
  std::string limiter;  // "cfl (velocity)", "water wave speed", "soil elastic wave speed", "dt_max"
};

// What the stable time step needs of the particles, over all ranks: the fastest one's speed and
// which species have particles.
struct ParticleExtremes {
  double fastest = 0;  // m/s
  bool water = false, soil = false;
};

// Sums over the particles of a species or the outflow record.
template <int Dim>
struct Outflow {
  double water_mass = 0, soil_mass = 0;  // kg that left through open sides
  double shear_eroded_volume = 0;        // m^3 of it the excess-stress erosion had taken (BedShear::eroded_volume)
  // m^3 the excess-stress law took from the beds over the run (BedShear::erode()'s sums), gross of
  // the deposits: what a model without deposition (breach, foam-erosion) erodes. The same on every
  // rank. (Kept with the outflow record: both are the run's checkpointed sums.)
  double law_eroded_volume = 0;
  Vec<Dim> momentum = Vec<Dim>::Zero();  // their momentum when they left
};

template <int Dim>
class Simulation {
 public:
  // `comm` is needed for the consistent drag (a PETSc solve on it, inside a PetscSession, with the
  // options prefix "drag_"); the other schemes need none. A comm of more than one rank
  // decomposes the domain: every member below that says COLLECTIVE must then be called on every
  // rank, the particles are seeded on any ranks (distribute() spreads them) and water() and
  // soil() hold this rank's.
  explicit Simulation(const SimulationSettings<Dim>& settings, std::optional<mpi::Comm> comm = std::nullopt);
  // The decomposition holds on to grid_: a simulation stays where it was built.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  Particles<Dim>& water() { return water_; }
  Particles<Dim>& soil() { return soil_; }
  const Particles<Dim>& water() const { return water_; }
  const Particles<Dim>& soil() const { return soil_; }
  const SimulationSettings<Dim>& settings() const { return s_; }
  const BlockGrid<Dim>& grid() const { return grid_; }
  const Outflow<Dim>& outflow() const { return outflow_; }
  // The inlet, or nullptr when the scene has none.
  const Inlet<Dim>* inlet() const { return inlet_ ? &*inlet_ : nullptr; }
  // Water mass the inlet has emitted, kg (0 without an inlet).
  double inflow_mass() const { return inlet_ ? inlet_->state().mass : 0.0; }

  double time() const { return time_; }
  // The consistent drag's last KSP solve (zero before the first, or for the other schemes).
  const SolveStats& drag_stats() const { return drag_stats_; }
  // The implicit forces' last Newton-Krylov solve and iteration counts (zero with explicit forces).
  const ImplicitState<Dim>& implicit() const { return implicit_; }
  long long steps() const { return steps_; }
  // The bed-shear closure's columns as of the last step's start, or nullptr without the closure.
  const BedShear<Dim>* bed_shear() const { return bed_shear_ ? &*bed_shear_ : nullptr; }
  // This rank's time per phase of step() since the simulation was built (model/step_timers.hpp).
  const StepTimes& step_times() const { return times_; }

  // The largest stable dt now: cfl h / max |v_p|, cfl h / c for the water's and the soil's wave
  // speeds (explicit forces only), and dt_max. Drag never limits it (implicit). `known`: the
  // extremes of the particles as they are now, already reduced over the ranks (a run's blow-up
  // check has them), which saves the scan and its reduction; without them COLLECTIVE.
  StepLimit stable_dt(const std::optional<ParticleExtremes>& known = std::nullopt) const;

  // Advances by dt. COLLECTIVE.
  void step(double dt);

  // Over several ranks: partitions the blocks of the particles seeded so far with METIS and sends
  // each particle to its owner. Nothing on one rank. COLLECTIVE.
  void distribute();
  // The decomposition, or nullptr on one rank.
  const DomainDecomposition<Dim>* decomposition() const { return dd_ ? &*dd_ : nullptr; }
  DomainDecomposition<Dim>* decomposition() { return dd_ ? &*dd_ : nullptr; }
  // The sum of a value over the ranks (the value itself on one rank). COLLECTIVE.
  double sum_over_ranks(double v) const { return dd_ ? dd_->waited().time([&] { return dd_->comm().sum(v); }) : v; }
  double max_over_ranks(double v) const { return dd_ ? dd_->waited().time([&] { return dd_->comm().max(v); }) : v; }
  // The largest of each value over the ranks, in place (one reduction). COLLECTIVE.
  void max_over_ranks(std::span<double> values) const {
    if (dd_) dd_->waited().time([&] { dd_->comm().all_reduce(values, mpi::Comm::Reduction::max); });
  }

  // The soil particles of this rank that the last step's erosion detached from the bed.
  std::size_t detached() const { return detached_.size(); }

  // Sets the clock, step count and outflow record of a run read back from a checkpoint (the
  // particles are set through water() and soil()).
  void restore(double time, long long steps, const Outflow<Dim>& outflow, const InletState& inlet) {
    stress_known_.clear();  // the particles are new: no stress is known
    time_ = time;
    steps_ = steps;
    outflow_ = outflow;
    if (inlet_) inlet_->restore(inlet);
  }

  // Kinetic energy of both species, J (J/m in 2D). COLLECTIVE.
  double kinetic_energy() const;

 private:
  void build_grid();
  void touch(const Particles<Dim>& P, std::vector<int>& groups);
  void touch_part(const Particles<Dim>& P, std::vector<int>& groups, std::optional<ParticleRun> run);
  void touch_part(const Particles<Dim>& P, std::vector<Index<Dim>>& reached, ParticleRun run);
  void stresses();
  void particles_to_grids(double dt);
  // P2G of a species' particles (or of particles in its order and places, the implicit forces'
  // probes) with its schedule.
  void spread(const Particles<Dim>& P, ColourSchedule<Dim>& schedule, const P2GSources<Dim>& in,
              NodeFields<Dim>& nodes);
  void spread_part(const Particles<Dim>& P, const P2GSources<Dim>& in, NodeFields<Dim>& nodes);
  // f(k, runs) for each part k, parts taken by the threads as they come free.
  template <class F>
  void in_parts(const SweepParts& parts, F&& f);
  // f(run) for runs that together cover particles 0 .. particles - 1: one run on one thread, parts
  // of kPart particles with threads.
  template <class F>
  void for_parts(std::size_t particles, F&& f);
  void update_particles(double dt);
  void update_soil(double dt, ParticleRun run);
  void remove_outflow();
  void keep_known_stresses();
  void size_stresses();
  void solve_grid(double dt);
  void solve_grid_implicit(double dt);  // model/implicit_forces.cpp
  bool implicit_residual(const double* x, double* r, double dt, double t_next);
  bool trial_forces(double dt);
  void trial_stresses(double dt);
  void constrain(double t_next);
  template <class F>
  void for_each_unknown(F&& f);
  void set_unknown_velocities(const double* x);
  void add_loads();
  void solid_fractions();
  void mixture_volume_rates(double dt);
  void water_velocities();
  void water_velocities_part(std::span<const ParticleRun> runs);
  void velocities_before(StepPhase p2g, NodeFields<Dim>& before);
  void wall_water_fill();
  void soil_velocities();
  void soil_velocities_part(std::span<const ParticleRun> runs);
  void carry_suspended();
  void sort_water();
  void free_water_velocities(double dt);
  void sample(const NodeFields<Dim>& nodes, const WallFold<Dim>& walls);
  void record_homes(const Particles<Dim>& P);
  void record_homes(const Particles<Dim>& P, ParticleRun run);
  void mark_moved(const Particles<Dim>& P, std::vector<char>& left);
  void mark_moved(const Particles<Dim>& P, std::vector<char>& left, ParticleRun run) const;
  // Times the rest of the enclosing scope as `phase` (waits counted over several ranks).
  StepPhaseScope phase(StepPhase p) { return {times_, p, wait_clock()}; }
  const WaitClock* wait_clock() const { return dd_ ? &dd_->waited() : nullptr; }

  SimulationSettings<Dim> s_;
  Particles<Dim> water_, soil_;
  BlockGrid<Dim> grid_;
  Walls<Dim> water_walls_;    // the walls as the water sees them (Walls::for_water())
  WallFold<Dim> fold_;        // the walls' mirror condition in the soil's transfers
  WallFold<Dim> water_fold_;  // and in the water's
  WallFold<Dim> shape_fold_;  // and in the soil's shape for the free water (coupling/free_water.hpp)
  NodeFields<Dim> water_nodes_, soil_nodes_;
  // With the free-water field: the free water's nodes (water_nodes_ then holds the pore water's),
  // its velocities before the forces (a FLIP share), the soil's shape (mass and offsets), the
  // soil's fill per slot, and per water particle 1 where it is free.
  NodeFields<Dim> free_nodes_, free_before_, shape_nodes_;
  NodeFields<Dim> carrier_;           // its momentum per node (velocity), which carries detached soil
  std::vector<double> carried_mass_;  // and its mass at each detached soil particle
  std::vector<double> soil_fill_;
  std::vector<char> free_water_;
  // With a FLIP share: each species' node velocities from its particles before the step's forces
  // (the mass and momentum its P2G spreads beside the forces), which G2P blends in
  // (transfer/apic.hpp, FlipBlend). probe_:
  // points at which sample() reads a grid field's velocity (the detached soil's water velocity).
  NodeFields<Dim> water_before_, soil_before_;
  Particles<Dim> probe_;
  std::vector<Mat<Dim>> grad_v_;             // the soil's velocity gradients
  std::vector<double> divergence_;           // the water's div v
  std::vector<double> water_fill_;           // m_w,i / I_i per node slot, for the saturation
  std::vector<double> soil_drag_, solid_volume_, water_pressure_;
  std::vector<double> solid_fraction_;  // mixture: phi_s per node slot
  // Per soil particle, its Kirchhoff stress, and 1 where that is the stress of its F_E as the
  // return mapping had it at hand (update_soil: 99.5% of the soil's particle-steps in example 2),
  // 0 where stresses() computes it. Both travel with the particles (the group order, the outflow,
  // the migration); a particle whose F_E changes elsewhere must have its flag cleared: those the
  // bed shear detaches (F_E = I, detached_), all of them where a checkpoint is read back
  // (restore()). Before 2026-11-29 each known stress kept its F_E, compared bit for bit with the
  // particle's in stresses(), whose pass then moved 152 bytes a soil particle in 2D against 49
  // now (example 2 at h = 0.025 m, 300 steps: the stresses phase 0.57 -> 0.32 s on one rank, the
  // step 2.6% faster, 4.0% on 2 ranks; medians of 5 paired runs, results bit for bit the same).
  std::vector<Mat<Dim>> soil_tau_;
  std::vector<char> stress_known_;
  // Over several ranks, per water and soil particle: 1 where the step's move took it to another
  // home block (only these can have left this rank's blocks; migrate() looks up just them).
  std::array<std::vector<char>, 2> left_home_;
  // remove_outflow(): the particles of a species that left the domain, per part and in all.
  std::vector<std::vector<std::size_t>> left_in_part_;
  std::vector<std::size_t> left_;
  std::vector<std::size_t> detached_;                      // the soil particles the step's erosion detached
  std::vector<typename BlockGrid<Dim>::Key> home_before_;  // one species' home blocks before the move
  std::optional<mpi::Comm> comm_;
  std::unique_ptr<ConsistentDrag<Dim>> consistent_;
  SolveStats drag_stats_{};
  std::unique_ptr<NewtonKrylov> newton_;  // with implicit forces
  ImplicitState<Dim> implicit_;
  Outflow<Dim> outflow_;
  std::optional<Inlet<Dim>> inlet_;
  std::optional<DomainDecomposition<Dim>> dd_;
  std::optional<BedShear<Dim>> bed_shear_;
  // With threads: the parts of a G2P or particle update, each species' P2G parts by colour.
  SweepParts parts_;
  ColourSchedule<Dim> water_schedule_, soil_schedule_;
  std::vector<int> colour_rank_;                  // the blocks' places in colour order (colour_ranks)
  std::vector<std::vector<Index<Dim>>> reached_;  // touch(): the blocks each part's stencils reach
  double time_ = 0;
  long long steps_ = 0;
  StepTimes times_;
};

// Simulation<2> and Simulation<3> are instantiated in simulation.cpp, where the members are
// defined. (No `extern template` here: GCC makes no target clones, kernels/vector_clones.hpp, of
// members of a class that was declared extern before their definition.)

}  // namespace suite::mpm2grid
