#include "solvers/mpm2grid/run/run_mpm.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "core/checkpoint/checkpoint.hpp"
#include "core/checkpoint/scene_match.hpp"
#include "core/checkpoint/schedule.hpp"
#include "core/io/csv_series.hpp"
#include "core/io/output_dir.hpp"
#include "core/io/xdmf.hpp"
#include "core/log/progress.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/run/memory_check.hpp"
#include "core/run/phase_timers.hpp"
#include "core/run/run_record.hpp"
#include "core/petsc/petsc_session.hpp"
#include "core/run/signals.hpp"
#include "solvers/mpm2grid/io/checkpoint_state.hpp"
#include "solvers/mpm2grid/io/dam_measures.hpp"
#include "solvers/mpm2grid/io/particle_output.hpp"
#include "solvers/mpm2grid/model/blow_up.hpp"
#include "solvers/mpm2grid/scenes/memory_estimate.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

// What the steps after a failed implicit solve count as their limit (run.json's dt_limiters).
constexpr const char* kImplicitLimiter = "implicit solve (dt cut after a failed Newton-Krylov solve)";

// series.csv. Masses are per metre of thickness in 2D (kg/m), as are the volumes (m^2) and the
// discharges (m^2/s).
template <int Dim>
std::vector<io::CsvColumn> series_columns() {
  const std::string volume = Dim == 2 ? "m^2" : "m^3", discharge = Dim == 2 ? "m^2/s" : "m^3/s";
  return {{"time", "s"},
          {"dt", "s"},
          {"water_front", "m"},
          {"water_mass", "kg"},
          {"soil_mass", "kg"},
          {"outflow_water_mass", "kg"},
          {"outflow_soil_mass", "kg"},
          {"inflow_water_mass", "kg"},
          {"outflow_water_discharge", discharge},
          {"outflow_soil_discharge", discharge},
          {"eroded_soil_volume", volume},
          {"crest_height", "m"},
          {"kinetic_energy", "J"},
          {"water_particles", ""},
          {"soil_particles", ""},
          {"bed_shear_max", "Pa"},  // the bed-shear closure's largest shear at the last step's start (0 without it)
          {"suspended_soil_volume", volume},  // as placed, of the soil the excess-stress erosion detached
          {"shear_eroded_volume", volume},    // what the excess-stress erosion took (shear_eroded_volume())
          {"law_eroded_volume", volume}};     // what its law took, gross of deposits (Outflow::law_eroded_volume)
}

// profiles.csv: the crest profile (io/dam_measures.hpp) at every particle output time.
const std::vector<io::CsvColumn> kProfileColumns{{"time", "s"}, {"x", "m"}, {"top_y", "m"}};

// The farthest water particle along x plus half a particle spacing: the surge front of a
// collapsing column (Martin & Moyce measured the leading edge). COLLECTIVE.
template <int Dim>
double water_front(const Simulation<Dim>& sim, double half_spacing) {
  double front = -std::numeric_limits<double>::infinity();
  for (const auto& x : sim.water().x) front = std::max(front, x[0]);
  front = sim.max_over_ranks(front);
  return std::isfinite(front) ? front + half_spacing : std::nan("");
}

constexpr const char* kSolver = "mpm2grid";
constexpr long long kCheckpointFormat = 6;  // 2: inlet state, outlet record, initial soil volume; 3: block owners;
                                            // 4: particle loads (surcharges); 5: particle ids; 6: the scene's keys

// A scene with its threads per rank (SimulationSettings::threads): OMP_NUM_THREADS, the usual
// knob (slurm/mpm2grid.sbatch sets it from --cpus-per-task), else 1. Not OpenMP's own default of
// every core the process may use: each of 16 ranks on a node would start 16 threads.
template <int Dim>
Scene<Dim> with_threads(Scene<Dim> scene) {
  const char* value = std::getenv("OMP_NUM_THREADS");
  if (!value || !*value) return scene;
  char* end = nullptr;
  const long n = std::strtol(value, &end, 10);
  if (*end != '\0' || n < 1 || n > 1024)
    throw InputError(
        fmt::format("OMP_NUM_THREADS = '{}': mpm2grid takes one whole number of threads per rank "
                    "(1 to 1024; unset it for one)",
                    value));
  scene.simulation.threads = static_cast<int>(n);
  return scene;
}

// The scene keys a restart may change: when to stop, how often to sample and write, checkpoint
// settings and the load-balancing knobs (the partition changes sums only at round-off). Every
// other key is the checkpoint's physics and must stay. A later time.end extends a run.
const std::vector<std::string> kMayChangeOnRestart{"time.end", "time.max_steps", "time.series", "time.output",
                                                   "checkpoint", "decomposition"};

template <int Dim>
class MpmRun {
 public:
  MpmRun(const mpi::Comm& comm, const config::Config& cfg, const RunOptions& o, Logger& log)
      : comm_(comm),
        scene_(with_threads(read_scene<Dim>(cfg))),
        scene_keys_(cfg),
        log_(log),
        record_(comm, kSolver, o.argv),
        petsc_(petsc_session(comm, scene_)),
        sim_(scene_.simulation, comm) {
    out_ = io::prepare_output_dir(comm, o.out);
    io::prepare_output_dir(comm, out_ / "particles");
    checkpoints_ = io::prepare_output_dir(comm, out_ / "checkpoints");
    mpi::collective_try(comm, [&] {
      if (!comm.is_root()) return;
      cfg.write_effective(out_ / "effective_config.yaml");
      log.add_file(out_ / "log.txt");
    });
    half_spacing_ = 0.5 * scene_.simulation.h / scene_.particles_per_cell;
  }

  int run(const std::optional<std::string>& restart) {
    const auto memory = estimate_memory(scene_);
    const double bytes = memory.bytes + memory.bytes_per_rank * comm_.size();
    record_.extra()["memory_estimate"] = {{"bytes", bytes},
                                          {"soil_particles", memory.soil_particles},
                                          {"water_particles", memory.water_particles},
                                          {"grid_nodes", memory.nodes}};
    require_memory(comm_, bytes, fmt::format("scene {}", scene_.name), memory.breakdown(),
                   "coarsen grid.spacing, lower grid.particles_per_cell or run on more nodes");
    if (restart) {
      resume(*restart);
    } else {
      // a fresh start: checkpoints of an earlier run are stale
      checkpoint::discard_after(comm_, checkpoints_, "checkpoint", -1, log_);
      // Each rank seeds a band of the lattice; over several ranks METIS then partitions the blocks
      // and the particles go to their owners.
      seed_particles(scene_, sim_, &comm_);
      sim_.distribute();
      p_.initial_soil_volume = soil_in_dam();
      p_.next_sample = scene_.time.series;
      p_.next_output = scene_.time.output;
      p_.smallest_dt = std::numeric_limits<double>::infinity();
      start_outputs(false);
      sample(0);
      output();
    }
    // The steps' traffic, without the first distribution's (half of every rank's band moves).
    if (const auto* dd = sim_.decomposition()) traffic_before_ = dd->stats();
    log_.info("{}D scene {}: h = {} m, {} water and {} soil particles, drag {}, {}", Dim, scene_.name,
              scene_.simulation.h, count(sim_.water()), count(sim_.soil()), drag_name(scene_.simulation.drag),
              implicit() ? "implicit forces (backward Euler, PETSc SNES with prefix implicit_: Newton + GMRES, "
                           "matrix-free)"
                         : "explicit forces");
    if (comm_.size() > 1) {
      const auto per_rank = comm_.all_gather(static_cast<long long>(sim_.water().size() + sim_.soil().size()));
      log_.info("domain decomposed over {} ranks (METIS on the grid blocks; halo 2 cells): particles per rank {}",
                comm_.size(), fmt::join(per_rank, ", "));
    }
    if (sim_.soil().size() > 0) {
      const auto& soil = scene_.simulation.soil.material;
      log_.info("soil: dry cohesion c0 = {:.6g} Pa, friction angle {:.4g} deg", soil.cohesion,
                soil.friction_angle * 180 / std::numbers::pi);
      const auto& s = scene_.simulation;
      if (s.buoyancy)
        log_.info("pore pressure: {}", s.mixture ? "mixture (the pore water is compressed with the skeleton, Biot)"
                                                 : "buoyancy only (the water does not see the solid's volume)");
    }
    if (const auto* inlet = sim_.inlet())
      log_.info("inlet on x_low: {} particle rows ({} m of the {} m asked for), q(0) = {} m^2/s per metre, v(0) = {} "
                "m/s; layer mass {} kg",
                inlet->rows(), inlet->section_height(), inlet->settings().height, inlet->settings().discharge(0),
                inlet->velocity(0), inlet->layer_mass());
    SignalWatcher signals(out_);
    checkpoint::Schedule schedule(scene_.checkpoints);
    ProgressLine progress(log_, sim_.time(), scene_.time.end);
    const long long first_step = sim_.steps();
    first_step_ = first_step;
    const double end = scene_.time.end * (1 - 1e-12);
    while (sim_.time() < end) {
      advance();
      progress.report(sim_.steps(), sim_.time(), last_dt_);
      const SignalRequest req = signals.poll(comm_);
      const bool max_reached = scene_.time.max_steps > 0 && sim_.steps() - first_step >= scene_.time.max_steps &&
                               sim_.time() < end;
      const auto why = checkpoint::checkpoint_or_stop(
          comm_, schedule, sim_.steps(), req,
          max_reached ? std::optional(fmt::format("time.max_steps = {}", scene_.time.max_steps)) : std::nullopt,
          [&] { write_checkpoint(); });
      if (why) {
        log_.warn("stopped at step {} (t = {} s) on {}; continue with --restart latest", sim_.steps(), sim_.time(),
                  *why);
        record_extras();
        write_record("stopped: " + *why);
        return 0;
      }
    }
    // The final state, so that a later time.end can extend the run (--restart latest).
    if (last_checkpoint_step_ != sim_.steps()) write_checkpoint();
    finish();
    return 0;
  }

 private:
  // One step of the adaptive size, cut to land on the next sample, output or end time; then the
  // samples and outputs due.
  void advance() {
    std::optional<ScopedPhase> checks(std::in_place, timers_, "dt limit");
    // The last blow-up check scanned the particles as they are now: its extremes save a scan.
    StepLimit limit = sim_.stable_dt(std::exchange(extremes_, std::nullopt));
    checks.reset();
    // The step the scene's limits allow (the floor of the cuts below is a thousandth of it).
    const double allowed = limit.dt;
    // The implicit forces' step after a Newton-Krylov solve failed: halved at each failure, it
    // grows back by 1.25 a step.
    if (p_.dt_cap < limit.dt)
      limit = {p_.dt_cap, kImplicitLimiter};
    else
      p_.dt_cap = std::numeric_limits<double>::infinity();  // grown back to the limits
    const double to_event = std::min({p_.next_sample, p_.next_output, scene_.time.end}) - sim_.time();
    double dt = std::min(limit.dt, to_event);
    particle_steps_[0] += static_cast<long long>(sim_.water().size());
    particle_steps_[1] += static_cast<long long>(sim_.soil().size());
    {
      ScopedPhase phase(timers_, "step");
      for (;;) {
        try {
          sim_.step(dt);
          break;
        } catch (const ImplicitSolveFailed& failed) {
          // Nothing of the step's state has changed before the solve: the step is taken again.
          // Against the limits, not the cut step: steps that each fail once and pass at half
          // the dt would otherwise halve it for ever.
          if (dt < 1e-3 * std::min(allowed, to_event))
            throw InputError(fmt::format("{}; it failed down to dt = {:.4g} s, a thousandth of the step the scene's "
                                         "limits allow: check the scene's materials and walls",
                                         failed.what(), dt));
          log_.warn("{}; taking the step again with dt = {:.4g} s", failed.what(), dt / 2);
          dt /= 2;
          limit = {dt, kImplicitLimiter};
          p_.dt_cap = dt;
        }
      }
    }
    if (sim_.detached() > 0)
      log_.debug("step {} (t = {} s): the erosion detached {} soil particles from the bed on rank {}", sim_.steps(),
                 sim_.time(), sim_.detached(), comm_.rank());
    ++p_.limiters[limit.limiter];
    p_.dt_cap *= 1.25;  // infinity stays infinity
    drag_iterations_ = std::max(drag_iterations_, static_cast<long long>(sim_.drag_stats().iterations));
    drag_owned_nodes_ += sim_.drag_stats().owned_nodes;
    drag_solved_nodes_ += sim_.drag_stats().solved_nodes;
    drag_seconds_[0] += sim_.drag_stats().rows_s;
    drag_seconds_[1] += sim_.drag_stats().exchange_s;
    drag_seconds_[2] += sim_.drag_stats().krylov_s;
    // After the first solve every solver has read its options: one nothing read is a mistake.
    if (petsc_ && sim_.steps() == first_step_ + 1)
      if (const auto unused = petsc_->unused_options(); !unused.empty())
        throw InputError(fmt::format("petsc_options: PETSc used no option named {}; check the spelling (the "
                                     "consistent drag's options start with -drag_, e.g. -drag_ksp_rtol 1e-10 "
                                     "-drag_pc_type jacobi; the implicit forces' with -implicit_, e.g. "
                                     "-implicit_snes_rtol 1e-8)",
                                     fmt::join(unused, ", ")));
    grid_block_steps_ += static_cast<long long>(sim_.grid().blocks());
    last_dt_ = dt;
    p_.smallest_dt = std::min(p_.smallest_dt, dt);
    checks.emplace(timers_, "blow-up check");
    const double inlet_velocity = sim_.inlet() ? sim_.inlet()->velocity(sim_.time()) : 0.0;
    const double speed_limit = BlowUpCheck::speed_limit(scene_.simulation, inlet_velocity);
    // The worst particle of any rank, in one reduction: every rank stops with the same message.
    const std::array<const Particles<Dim>*, 2> species_list{&sim_.water(), &sim_.soil()};
    // Per species: 1 when some position or velocity is not finite, the top speed, 1 when it has
    // particles.
    std::array<double, 6> worst{};
    for (std::size_t k = 0; k < 2; ++k) {
      const auto local = ParticleScan<Dim>::of(*species_list[k], scene_.simulation.threads);
      worst[3 * k] = local.finite ? 0.0 : 1.0;
      worst[3 * k + 1] = local.finite ? local.speed : 0.0;
      worst[3 * k + 2] = species_list[k]->size() > 0 ? 1.0 : 0.0;
    }
    sim_.max_over_ranks(worst);
    for (std::size_t k = 0; k < 2; ++k) {
      const bool finite = worst[3 * k] == 0;
      const double speed = worst[3 * k + 1];
      const char* species = k == 0 ? "water" : "soil";
      // A step cut to land on a sample, output or end time names the limit it was cut from.
      const auto limited = dt < limit.dt
                               ? fmt::format("cut to land on a sample or output time from {:.4g} s limited by {}",
                                             limit.dt, limit.limiter)
                               : fmt::format("limited by {}", limit.limiter);
      const auto where = fmt::format("the run blew up at step {} (t = {:.6g} s, dt = {:.4g} s {})", sim_.steps(),
                                     sim_.time(), dt, limited);
      const auto fix = fmt::format("the last good checkpoint is kept in {}; lower time.cfl or time.dt_max{}",
                                   checkpoints_.string(),
                                   scene_.simulation.drag == DragScheme::explicit_euler
                                       ? ", or use drag: lumped (explicit drag is unstable above dt = 2 tau_d)"
                                       : "");
      if (!finite)
        throw InputError(fmt::format("{}: a {} particle's position or velocity is not finite; {}", where, species, fix));
      if (speed > speed_limit)
        throw InputError(fmt::format("{}: energy blow-up, a {} particle moves at {:.4g} m/s, more than {} times the "
                                     "{:.4g} m/s that falling through the domain and the inflow can give; {}",
                                     where, species, speed, BlowUpCheck::kFactor,
                                     speed_limit / BlowUpCheck::kFactor, fix));
    }
    extremes_ = ParticleExtremes{std::max(worst[1], worst[4]), worst[2] > 0, worst[5] > 0};
    checks.reset();
    const double end = scene_.time.end * (1 - 1e-12);
    if (sim_.time() >= p_.next_sample * (1 - 1e-12)) {
      sample(dt);
      p_.next_sample += scene_.time.series;
    }
    if (sim_.time() >= p_.next_output * (1 - 1e-12) || sim_.time() >= end) {
      output();
      p_.next_output += scene_.time.output;
    }
  }

  // Rank 0 owns the CSV and XDMF files; a problem with them stops every rank. COLLECTIVE.
  void start_outputs(bool resuming) {
    mpi::collective_try(comm_, [&] {
      if (!comm_.is_root()) return;
      const double t = sim_.time();
      csv_ = resuming ? io::CsvSeries::resume_at(out_ / "series.csv", series_columns<Dim>(), t)
                      : io::CsvSeries(out_ / "series.csv", series_columns<Dim>());
      profiles_ = resuming ? io::CsvSeries::resume_at(out_ / "profiles.csv", kProfileColumns, t)
                           : io::CsvSeries(out_ / "profiles.csv", kProfileColumns);
      xdmf_.emplace(out_ / "particles.xmf");
      if (resuming) xdmf_->resume_at(t);
    });
  }

  // The outlet record moves on every sample, on every rank (it is checkpointed state).
  void sample(double dt) {
    ScopedPhase phase(timers_, "output");
    const auto& s = scene_.simulation;
    const auto& out = sim_.outflow();
    const Discharges q = p_.outlet.sample(sim_.time(), out.water_mass, out.soil_mass, s.water.density, s.soil.density);
    // Every rank takes part in the sums; rank 0 writes them.
    const std::vector<double> row{sim_.time(),
                                  dt,
                                  water_front(sim_, half_spacing_),
                                  mass(sim_.water()),
                                  mass(sim_.soil()),
                                  out.water_mass,
                                  out.soil_mass,
                                  sim_.inflow_mass(),
                                  q.water,
                                  q.soil,
                                  eroded_volume(),
                                  crest_height(profile(), floor()),
                                  sim_.kinetic_energy(),
                                  static_cast<double>(count(sim_.water())),
                                  static_cast<double>(count(sim_.soil())),
                                  sim_.bed_shear() ? sim_.bed_shear()->largest_shear() : 0.0,
                                  suspended_volume(),
                                  shear_eroded_volume(),
                                  out.law_eroded_volume};
    if (csv_) csv_->append(row);
  }

  // Over all ranks. COLLECTIVE.
  double mass(const Particles<Dim>& P) const { return sim_.sum_over_ranks(P.total_mass()); }
  double suspended_volume() const {
    const auto* b = sim_.bed_shear();
    double m = 0;
    if (b && scene_.simulation.erosion.on)
      for (std::size_t p = 0; p < sim_.soil().size(); ++p)
        if (b->suspended(sim_.soil(), p)) m += sim_.soil().mass[p];
    return sim_.sum_over_ranks(m) / scene_.simulation.soil.density;
  }
  // The soil the excess-stress erosion took from the bed, net of its deposits: the detached and
  // the partly eroded particles' volumes (BedShear::eroded_volume), with those of the particles
  // that left through the outlet; 0 without that erosion. COLLECTIVE.
  double shear_eroded_volume() const {
    const auto* b = sim_.bed_shear();
    if (!b || !scene_.simulation.erosion.on) return 0;
    double v = 0;
    for (std::size_t p = 0; p < sim_.soil().size(); ++p) v += b->eroded_volume(sim_.soil(), p);
    return sim_.sum_over_ranks(v) + sim_.outflow().shear_eroded_volume;
  }
  long long count(const Particles<Dim>& P) const { return comm_.sum(static_cast<long long>(P.size())); }

  double floor() const { return scene_.simulation.walls.lo[1]; }
  // The crest profile of every rank's soil (io/dam_measures.hpp): the cells' counts summed over
  // the ranks, up to the highest soil particle. COLLECTIVE.
  std::vector<ColumnTop> profile() const {
    const auto& walls = scene_.simulation.walls;
    const double x0 = walls.lo[0], h = scene_.simulation.h, spacing = 2 * half_spacing_;
    double highest = floor();
    for (const auto& x : sim_.soil().x) highest = std::max(highest, x[1]);
    highest = sim_.max_over_ranks(highest);
    const auto columns = static_cast<long>(std::llround((walls.hi[0] - x0) / h)) + 1;
    const auto rows = static_cast<long>(std::floor((highest - floor()) / h)) + 1;
    const double depth = Dim == 3 ? walls.hi[Dim - 1] - walls.lo[Dim - 1] : 1.0;
    auto cells = soil_columns(sim_.soil(), x0, floor(), h, columns, rows, std::pow(spacing, Dim) / (h * h * depth));
    if (comm_.size() > 1) comm_.all_reduce(cells.count, mpi::Comm::Reduction::sum);
    return crest_profile(cells);
  }
  // The as-placed volume of the soil still in the dam's initial cross-section grown by half a
  // particle spacing (io/dam_measures.hpp). COLLECTIVE.
  double soil_in_dam() const {
    const double count = static_cast<double>(count_within(sim_.soil(), scene_.soil_regions, half_spacing_));
    return sim_.sum_over_ranks(count) * std::pow(2 * half_spacing_, Dim);
  }
  double eroded_volume() const { return p_.initial_soil_volume - soil_in_dam(); }

  void output() {
    ScopedPhase phase(timers_, "output");
    write_particles(comm_, sim_, out_, fmt::format("particles/step_{:06d}.h5", sim_.steps()),
                    xdmf_ ? &*xdmf_ : nullptr);
    ++p_.files;
    if (count(sim_.soil()) == 0) return;
    const auto columns = profile();
    if (profiles_)
      for (const auto& c : columns) profiles_->append({sim_.time(), c.x, c.top});
  }

  void write_checkpoint() {
    ScopedPhase phase(timers_, "checkpoint");
    const auto path = checkpoint::file_name(checkpoints_, "checkpoint", sim_.steps());
    checkpoint::Writer w(comm_, path, {kSolver, kCheckpointFormat, sim_.steps(), sim_.time(), "", 0});
    w.write<unsigned char>("scene_keys", scene_keys_.bytes());
    write_state(w, sim_, p_);
    w.commit();
    if (comm_.is_root()) checkpoint::prune(checkpoints_, "checkpoint", scene_.checkpoints.keep);
    write_record(fmt::format("running: checkpoint at step {}", sim_.steps()));
    last_checkpoint_step_ = sim_.steps();
    log_.info("checkpoint {} written", path.filename().string());
  }


  void resume(const std::string& which) {
    const auto path = checkpoint::restart_path(comm_, checkpoints_, "checkpoint", which);
    checkpoint::Reader r(comm_, path, kSolver, kCheckpointFormat);
    const auto where = fmt::format("checkpoint '{}'", path.string());
    checkpoint::SceneRecord::from_bytes(r.read<unsigned char>("scene_keys"), where)
        .require_same(scene_keys_, kMayChangeOnRestart, where);
    checkpoint::require_later_end(scene_.time.end, r.header().time, where);
    read_state(r, sim_, p_);
    // A restart may change time.series or time.output (e.g. frequent outputs just before a
    // failure): a checkpointed next time that is not the interval's next multiple after now is
    // recomputed as that. One that is (to round-off: the run adds the interval up) is kept as it
    // is, so that a run restarted with unchanged settings repeats the uninterrupted run bit for bit.
    const auto next_event = [t = sim_.time()](double next, double interval) {
      const double k = std::floor(t / interval * (1 + 1e-12)) + 1;  // the next multiple's number
      return std::abs(next / interval - k) < 1e-6 ? next : k * interval;
    };
    p_.next_sample = next_event(p_.next_sample, scene_.time.series);
    p_.next_output = next_event(p_.next_output, scene_.time.output);
    last_checkpoint_step_ = sim_.steps();
    record_.extra()["restarted_from"] = path.string();
    // later ones belong to the run being replaced
    checkpoint::discard_after(comm_, checkpoints_, "checkpoint", sim_.steps(), log_);
    log_.info("restarting from {} at step {} (t = {} s)", path.filename().string(), sim_.steps(), sim_.time());
    start_outputs(true);
  }

  void finish() {
    Summary summary;
    summary.set("end_time", sim_.time(), "s");
    summary.set("steps", static_cast<double>(sim_.steps()));
    summary.set("smallest_dt", p_.smallest_dt, "s");
    summary.set("water_front", water_front(sim_, half_spacing_), "m");
    summary.set("water_mass", mass(sim_.water()), "kg");
    summary.set("soil_mass", mass(sim_.soil()), "kg");
    summary.set("outflow_water_mass", sim_.outflow().water_mass, "kg");
    summary.set("outflow_soil_mass", sim_.outflow().soil_mass, "kg");
    const auto& s = scene_.simulation;
    const std::string volume = Dim == 2 ? "m^2" : "m^3", discharge = Dim == 2 ? "m^2/s" : "m^3/s";
    summary.set("inflow_water_volume", sim_.inflow_mass() / s.water.density, volume);
    summary.set("outflow_water_volume", sim_.outflow().water_mass / s.water.density, volume);
    summary.set("outflow_soil_volume", sim_.outflow().soil_mass / s.soil.density, volume);
    summary.set("peak_water_outflow", p_.outlet.peak_water_discharge, discharge);
    summary.set("time_to_peak", p_.outlet.peak_time, "s");
    summary.set("initial_soil_volume", p_.initial_soil_volume, volume);
    summary.set("eroded_soil_volume", eroded_volume(), volume);
    summary.set("shear_eroded_volume", shear_eroded_volume(), volume);
    summary.set("law_eroded_volume", sim_.outflow().law_eroded_volume, volume);
    summary.set("final_crest_height", crest_height(profile(), floor()), "m");
    mpi::collective_try(comm_, [&] {
      if (comm_.is_root()) summary.write(out_ / "summary.json");
    });
    std::string limits;
    for (const auto& [why, n] : p_.limiters)
      limits += fmt::format("{}{}: {} steps", limits.empty() ? "" : ", ", why, n);
    record_extras();
    write_record("completed");
    log_.info("done: {} steps to t = {} s (dt limited by {}); {} particle files", sim_.steps(), sim_.time(), limits,
              p_.files);
  }

  // run.json with the step's phases (model/step_timers.hpp) beside the run's: "step/<phase>",
  // over several ranks "step/<phase>/wait" (blocked in MPI), and "step/<phase>/cpu" (the main
  // thread's CPU outside the waits), each with this run's steps as its calls. COLLECTIVE.
  void write_record(const std::string& status) {
    PhaseTimers all = timers_;
    const StepTimes& t = sim_.step_times();
    const long long steps = sim_.steps() - first_step_;
    for (std::size_t k = 0; k < kStepPhases; ++k) {
      const std::string name = std::string("step/") + kStepPhaseNames[k];
      if (t.seconds[k] == 0) continue;  // a phase this rank never ran (the halo's on one rank)
      all.add(name, t.seconds[k], steps);
      if (t.waited[k] > 0) all.add(name + "/wait", t.waited[k], steps);
      all.add(name + "/cpu", t.cpu[k], steps);
    }
    record_.write(out_ / "run.json", all, status);
  }

  // What run.json holds beside the timers, for a finished or a stopped run. COLLECTIVE.
  void record_extras() {
    record_.extra()["dt_limiters"] = p_.limiters;
    if (scene_.simulation.drag == DragScheme::consistent) {
      record_.extra()["drag_ksp_max_iterations"] = drag_iterations_;
      // The solve's work per rank, per step (this run's steps, or since the restart), least, mean
      // and most over the ranks: the coupled nodes it owns (it assembles their rows) and those
      // whose rows it holds in the Krylov solve (every rank waits in the iterations' reductions
      // for the one with the most).
      const double steps = static_cast<double>(std::max(1LL, sim_.steps() - first_step_));
      const auto spread = [&](double mine) {
        return nlohmann::json{
            {"min", comm_.min(mine)}, {"mean", comm_.sum(mine) / comm_.size()}, {"max", comm_.max(mine)}};
      };
      record_.extra()["drag_coupled_nodes_per_rank"] = spread(static_cast<double>(drag_owned_nodes_) / steps);
      record_.extra()["drag_solved_nodes_per_rank"] = spread(static_cast<double>(drag_solved_nodes_) / steps);
      // Where the grid solve phase's time goes with this drag (SolveStats): each rank's seconds
      // over the run (or since the restart) computing its rows, in PETSc's assembly and in the
      // Krylov solves, least, mean and most.
      record_.extra()["drag_seconds_per_rank"] = {{"rows", spread(drag_seconds_[0])},
                                                  {"exchange", spread(drag_seconds_[1])},
                                                  {"krylov", spread(drag_seconds_[2])}};
    }
    if (implicit()) {
      // This run's (or its part since the restart: the counts start with the simulation), per step.
      const ImplicitState<Dim>& im = sim_.implicit();
      const double steps = static_cast<double>(std::max(1LL, sim_.steps() - first_step_));
      auto& j = record_.extra()["implicit_forces"];
      j["newton_per_step"] = static_cast<double>(im.newton_total) / steps;
      j["krylov_per_step"] = static_cast<double>(im.krylov_total) / steps;
      j["residual_evaluations_per_step"] = static_cast<double>(im.evaluations_total) / steps;
      j["newton_most_in_a_step"] = im.newton_most;
      j["krylov_most_in_a_step"] = im.krylov_most;
      if (scene_.simulation.clamp_passes > 1) {
        j["clamp_passes_per_step"] = static_cast<double>(im.passes_total) / steps;
        j["steps_with_clamp_side_changes"] = im.clamp_changed_steps;  // after the last pass
      }
    }
    if (const auto* dd = sim_.decomposition()) record_decomposition(*dd, sim_.steps() - first_step_);
    record_per_rank();
  }

  // Every rank's particle-steps of each species and seconds in each step phase (of those waiting
  // in MPI, and the main thread's CPU seconds outside the waits): whether the slowest rank of a
  // phase had more work, or took longer over the same work (its core: off it, when its wall time
  // outside the waits exceeds its CPU time), and whether it is the same rank in every phase.
  // COLLECTIVE.
  void record_per_rank() {
    const StepTimes& t = sim_.step_times();
    std::vector<double> mine{static_cast<double>(particle_steps_[0]), static_cast<double>(particle_steps_[1]),
                             static_cast<double>(grid_block_steps_)};
    mine.insert(mine.end(), t.seconds.begin(), t.seconds.end());
    mine.insert(mine.end(), t.waited.begin(), t.waited.end());
    mine.insert(mine.end(), t.cpu.begin(), t.cpu.end());
    const auto n = mine.size();
    std::vector<double> all(n * static_cast<std::size_t>(comm_.size()));
    SUITE_MPI_CHECK(MPI_Allgather(mine.data(), static_cast<int>(n), MPI_DOUBLE, all.data(), static_cast<int>(n),
                                  MPI_DOUBLE, comm_.raw()));
    const auto column = [&](std::size_t i) {
      std::vector<double> v;
      for (std::size_t r = 0; r < all.size(); r += n) v.push_back(all[r + i]);
      return v;
    };
    auto& j = record_.extra()["per_rank"];
    j["water_particle_steps"] = column(0);
    j["soil_particle_steps"] = column(1);
    j["grid_block_steps"] = column(2);
    for (std::size_t k = 0; k < kStepPhases; ++k) {
      const auto seconds = column(3 + k);
      if (*std::max_element(seconds.begin(), seconds.end()) == 0) continue;  // a phase no rank ran
      j["step_s"][kStepPhaseNames[k]] = seconds;
      j["wait_s"][kStepPhaseNames[k]] = column(3 + kStepPhases + k);
      j["cpu_s"][kStepPhaseNames[k]] = column(3 + 2 * kStepPhases + k);
    }
  }

  // The decomposition's traffic in run.json: sums over the ranks per step of this run's steps (or
  // of its part since the restart; the first distribution not counted), the load at the end.
  // COLLECTIVE.
  void record_decomposition(const DomainDecomposition<Dim>& dd, long long steps) {
    DecompositionStats st = dd.stats();
    const DecompositionStats& before = traffic_before_;
    st.halo_bytes -= before.halo_bytes, st.halo_messages -= before.halo_messages;
    st.migration_bytes -= before.migration_bytes, st.migration_messages -= before.migration_messages;
    st.migrated -= before.migrated;
    const double per_step = 1.0 / static_cast<double>(std::max(1LL, steps));
    auto& j = record_.extra()["decomposition"];
    j["ranks"] = comm_.size();
    j["steps"] = steps;
    j["rebalances"] = st.rebalances;
    j["rebalances_diffused"] = st.diffused;
    j["rebalance_migrated_particles"] = comm_.sum(st.rebalance_migrated - before.rebalance_migrated);
    j["rebalance_partition_s"] = comm_.max(st.partition_seconds - before.partition_seconds);
    j["imbalance_at_last_check"] = st.imbalance;
    if (scene_.simulation.decomposition.balance_wet_soil) j["wet_soil_imbalance_at_last_check"] = st.wet_soil_imbalance;
    j["halo_bytes_per_step"] = static_cast<double>(comm_.sum(st.halo_bytes)) * per_step;
    j["halo_messages_per_step"] = static_cast<double>(comm_.sum(st.halo_messages)) * per_step;
    j["migration_messages_per_step"] = static_cast<double>(comm_.sum(st.migration_messages)) * per_step;
    j["migrated_particles_per_step"] = static_cast<double>(comm_.sum(st.migrated)) * per_step;
    j["migration_bytes_per_step"] = static_cast<double>(comm_.sum(st.migration_bytes)) * per_step;
    j["claimed_blocks"] = st.claimed_blocks;
    j["particles_per_rank"] = comm_.all_gather(static_cast<long long>(sim_.water().size() + sim_.soil().size()));
  }

  bool implicit() const { return scene_.simulation.forces == ForceScheme::implicit_end; }

  // A PETSc session for the consistent drag and the implicit forces only.
  static std::unique_ptr<PetscSession> petsc_session(const mpi::Comm& comm, const Scene<Dim>& scene) {
    if (scene.simulation.drag != DragScheme::consistent && scene.simulation.forces != ForceScheme::implicit_end)
      return nullptr;
    return std::make_unique<PetscSession>(comm, scene.petsc_options);
  }

  static const char* drag_name(DragScheme d) {
    switch (d) {
      case DragScheme::lumped:
        return "lumped (implicit, closed form per node)";
      case DragScheme::consistent:
        return "consistent (implicit, PETSc KSP with prefix drag_; CG + Jacobi unless petsc_options say otherwise)";
      case DragScheme::explicit_euler:
        break;
    }
    return "explicit (forward Euler; unstable above dt = 2 tau_d)";
  }

  mpi::Comm comm_;
  Scene<Dim> scene_;
  checkpoint::SceneRecord scene_keys_;  // the scene as read, kept in every checkpoint
  Logger& log_;
  RunRecord record_;
  std::unique_ptr<PetscSession> petsc_;  // before sim_: the drag solver's objects go first
  PhaseTimers timers_;
  Simulation<Dim> sim_;
  std::filesystem::path out_, checkpoints_;
  double half_spacing_ = 0, last_dt_ = 0;
  DecompositionStats traffic_before_;  // the decomposition's counts when the steps began
  std::optional<ParticleExtremes> extremes_;  // the last blow-up check's, while the particles stay as it saw them
  long long drag_iterations_ = 0;  // most KSP iterations of one consistent drag solve in this run
  long long drag_owned_nodes_ = 0;      // coupled nodes this rank owned, summed over this run's steps
  long long drag_solved_nodes_ = 0;     // coupled nodes whose rows this rank held in the Krylov solve, the same
  std::array<double, 3> drag_seconds_{};       // this rank's seconds in the drag's rows, exchange and solves, the same
  std::array<long long, 2> particle_steps_{};  // water and soil particles at each step's start, summed
  long long grid_block_steps_ = 0;             // blocks of this rank's grid (owned and ghost) after each step, summed
  long long first_step_ = 0;            // the step this run (or its restart) began at
  long long last_checkpoint_step_ = -1;  // the step of the newest checkpoint of this run
  RunProgress p_;
  std::optional<io::CsvSeries> csv_;    // rank 0 only
  std::optional<io::CsvSeries> profiles_;  // rank 0 only
  std::optional<io::XdmfSeries> xdmf_;  // rank 0 only
};

}  // namespace

int run_mpm(const mpi::Comm& comm, const config::Config& scene, const RunOptions& options, Logger& log) {
  if (scene_dimension(scene) == 2) return MpmRun<2>(comm, scene, options, log).run(options.restart);
  return MpmRun<3>(comm, scene, options, log).run(options.restart);
}

}  // namespace suite::mpm2grid
