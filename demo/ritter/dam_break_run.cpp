#include "demo/ritter/dam_break_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/checkpoint/checkpoint.hpp"
#include "core/checkpoint/scene_match.hpp"
#include "core/checkpoint/schedule.hpp"
#include "core/errors.hpp"
#include "core/io/csv_series.hpp"
#include "core/io/h5_file.hpp"
#include "core/io/output_dir.hpp"
#include "core/io/xdmf.hpp"
#include "core/log/progress.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/run/phase_timers.hpp"
#include "core/run/run_record.hpp"
#include "core/run/signals.hpp"
#include "demo/ritter/ritter_solution.hpp"

namespace suite::demo {

namespace {

using config::Range;

constexpr const char* kSolver = "suite-demo";
constexpr long long kCheckpointFormat = 2;  // 2: the scene's keys

// The scene keys a restart may change: a later end extends the run; the rest only say when to
// stop and how often to write.
const std::vector<std::string> kMayChangeOnRestart{"time.end", "time.max_steps", "time.output", "checkpoint"};

struct Scene {
  double h0, reservoir_length, width, channel_length, gravity;
  long long cells;
  double t_end, sample, output;
  long long max_steps;
  checkpoint::ScheduleSettings checkpoints;
};

Scene read_scene(const config::Config& cfg) {
  const auto root = cfg.root();
  const auto res = root.section("reservoir");
  const auto channel = root.section("channel");
  const auto time = root.section("time");
  Scene s{};
  s.h0 = res.quantity("depth", "m", Range::positive());
  s.reservoir_length = res.quantity("length", "m", Range::positive());
  s.width = res.quantity("width", "m", 1.0, Range::positive());
  s.channel_length = channel.quantity("length", "m", Range::positive());
  s.gravity = root.quantity("gravity", "m/s^2", 9.81, Range::positive());
  s.cells = root.integer("cells", 4000, 2, 2'000'000'000);
  s.t_end = time.quantity("end", "s", Range::positive());
  s.sample = time.quantity("sample", "s", Range::positive());
  s.output = time.quantity("output", "s", s.t_end, Range::positive());
  s.max_steps = time.integer("max_steps", 0, 0, std::numeric_limits<long long>::max());
  s.checkpoints = checkpoint::ScheduleSettings::read(root.section_or_empty("checkpoint"), {50, 1800.0, 2});
  cfg.finish();

  const double wall_time = s.reservoir_length / std::sqrt(s.gravity * s.h0);
  if (s.t_end > wall_time)
    time.reject("end", fmt::format("must be <= reservoir.length / sqrt(g h0) = {:.4g} s, when the negative wave "
                                   "reaches the back wall; shorten time.end or lengthen the reservoir",
                                   wall_time));
  if (s.sample > s.t_end) time.reject("sample", fmt::format("must be <= time.end ({} s)", s.t_end));
  if (s.output < s.sample) time.reject("output", fmt::format("must be >= time.sample ({} s)", s.sample));
  return s;
}

// The contiguous block of cells this rank owns.
struct Block {
  long long first = 0, count = 0;
  double x_left = 0.0, dx = 0.0;
  double center(long long i) const { return x_left + (double(first + i) + 0.5) * dx; }
};

Block block_of(const mpi::Comm& comm, const Scene& s) {
  Block b;
  b.first = s.cells * comm.rank() / comm.size();
  b.count = s.cells * (comm.rank() + 1) / comm.size() - b.first;
  b.x_left = -s.reservoir_length;
  b.dx = (s.reservoir_length + s.channel_length) / double(s.cells);
  return b;
}

// Time-integrated state: all a restart needs to continue bit for bit.
struct Progress {
  long long step = 0;
  double outflow_volume = 0.0;  // m^3 through the channel end, trapezoidal in time
  double q_out_previous = 0.0;  // m^3/s at the previous sample
  double max_balance_error = 0.0;
  double peak_outflow = 0.0;
  double time_to_peak = 0.0;
};

const std::vector<io::CsvColumn> kColumns{
    {"time", "s"},           {"discharge_at_dam", "m^3/s"}, {"outflow", "m^3/s"},
    {"front_position", "m"}, {"volume_in_domain", "m^3"},   {"outflow_volume", "m^3"},
    {"balance_error", ""}};

class DamBreakRun {
 public:
  DamBreakRun(const mpi::Comm& comm, const Scene& s, checkpoint::SceneRecord keys, const DamBreakOptions& o,
              Logger& log)
      : comm_(comm),
        s_(s),
        scene_keys_(std::move(keys)),
        log_(log),
        ritter_(s.h0, s.gravity),
        block_(block_of(comm, s)),
        record_(comm, kSolver, o.argv) {
    out_ = io::prepare_output_dir(comm, o.out);
    io::prepare_output_dir(comm, out_ / "fields");
    checkpoints_ = io::prepare_output_dir(comm, out_ / "checkpoints");
    n_steps_ = static_cast<long long>(std::ceil(s.t_end / s.sample - 1e-9));
    output_every_ = std::max(1LL, std::llround(s.output / s.sample));
    initial_volume_ = s.h0 * s.reservoir_length * s.width;
  }

  const std::filesystem::path& out() const { return out_; }

  int run(const std::optional<std::string>& restart) {
    if (restart) {
      resume(*restart);
    } else {
      // a fresh start: checkpoints of an earlier run are stale
      checkpoint::discard_after(comm_, checkpoints_, "checkpoint", -1, log_);
      start_outputs(false);
      write_fields(0);
    }
    SignalWatcher signals(out_);
    checkpoint::Schedule schedule(s_.checkpoints);
    ProgressLine progress(log_, time_of(p_.step), s_.t_end);
    const long long first_step = p_.step;
    log_.info("Ritter dam break: h0 = {} m, c0 = {:.4f} m/s, {} cells on {} ranks, {} samples to t = {} s", s_.h0,
              ritter_.wave_speed(), s_.cells, comm_.size(), n_steps_, s_.t_end);
    while (p_.step < n_steps_) {
      advance();
      progress.report(p_.step, time_of(p_.step), s_.sample, p_.step == n_steps_);
      if (p_.step % output_every_ == 0 || p_.step == n_steps_) write_fields(p_.step);
      const SignalRequest req = signals.poll(comm_);
      const bool max_reached = s_.max_steps > 0 && p_.step - first_step >= s_.max_steps && p_.step < n_steps_;
      const auto why = checkpoint::checkpoint_or_stop(
          comm_, schedule, p_.step, req,
          max_reached ? std::optional(fmt::format("time.max_steps = {}", s_.max_steps)) : std::nullopt,
          [&] { write_checkpoint(); });
      if (why) {
        log_.warn("stopped at step {} (t = {} s) on {}; continue with --restart latest", p_.step, time_of(p_.step),
                  *why);
        record_.write(out_ / "run.json", timers_, "stopped: " + *why);
        return 0;
      }
    }
    // The final state, so that a later time.end can extend the run (--restart latest).
    if (last_checkpoint_step_ != p_.step) write_checkpoint();
    finish();
    return 0;
  }

 private:
  double time_of(long long step) const { return std::min(double(step) * s_.sample, s_.t_end); }

  // One sample: the volume in the domain (midpoint rule over the cells, summed over ranks),
  // the outflow at the channel end, and the water balance.
  void advance() {
    const double t_prev = time_of(p_.step);
    ++p_.step;
    const double t = time_of(p_.step);
    double local = 0.0;
    {
      ScopedPhase phase(timers_, "sample");
      for (long long i = 0; i < block_.count; ++i) local += ritter_.at(block_.center(i), t).depth;
      local *= block_.dx * s_.width;
    }
    double volume = 0.0;
    {
      ScopedPhase phase(timers_, "reduce");
      volume = comm_.sum(local);
    }
    const ShallowWaterState end = ritter_.at(s_.channel_length, t);
    const double q_out = s_.width * end.depth * end.velocity;
    p_.outflow_volume += 0.5 * (p_.q_out_previous + q_out) * (t - t_prev);
    p_.q_out_previous = q_out;
    if (q_out > p_.peak_outflow) {
      p_.peak_outflow = q_out;
      p_.time_to_peak = t;
    }
    const double balance = (volume + p_.outflow_volume - initial_volume_) / initial_volume_;
    p_.max_balance_error = std::max(p_.max_balance_error, std::abs(balance));
    if (csv_) {
      ScopedPhase phase(timers_, "output");
      csv_->append({t, s_.width * ritter_.unit_discharge_at_dam(), q_out,
                    std::min(ritter_.front_position(t), s_.channel_length), volume, p_.outflow_volume, balance});
    }
  }

  // Rank 0 owns the CSV and XDMF files; a problem with them stops every rank. COLLECTIVE.
  void start_outputs(bool resuming) {
    mpi::collective_try(comm_, [&] {
      if (!comm_.is_root()) return;
      const double t = time_of(p_.step);
      csv_ = resuming ? io::CsvSeries::resume_at(out_ / "discharge.csv", kColumns, t)
                      : io::CsvSeries(out_ / "discharge.csv", kColumns);
      xdmf_.emplace(out_ / "dam_break.xmf");
      if (resuming) xdmf_->resume_at(t);
    });
  }

  // Cell centres as a polyline (x, water surface) with depth, velocity and unit discharge.
  void write_fields(long long step) {
    ScopedPhase phase(timers_, "output");
    const double t = time_of(step);
    const std::string name = fmt::format("fields/step_{:06d}.h5", step);
    std::vector<double> xy, depth, velocity, q;
    std::vector<long long> segments;
    for (long long i = 0; i < block_.count; ++i) {
      const double x = block_.center(i);
      const ShallowWaterState w = ritter_.at(x, t);
      xy.insert(xy.end(), {x, w.depth});
      depth.push_back(w.depth);
      velocity.push_back(w.velocity);
      q.push_back(w.depth * w.velocity);
      const long long g = block_.first + i;
      if (g + 1 < s_.cells) segments.insert(segments.end(), {g, g + 1});
    }
    io::H5File f(comm_, out_ / name, io::H5File::Mode::create);
    const auto nodes = f.write_rows<double>("/cells/surface", xy, 2);
    f.write_rows<double>("/cells/depth", depth);
    f.write_rows<double>("/cells/velocity", velocity);
    f.write_rows<double>("/cells/unit_discharge", q);
    const auto lines = f.write_rows<long long>("/cells/segments", segments, 2);
    f.set_attribute("/", "time", t);
    f.set_attribute("/", "step", step);
    f.close();
    if (xdmf_) {
      io::XdmfGrid grid{"water_surface",
                        name,
                        io::XdmfTopology::polyline,
                        {"surface", "/cells/surface", nodes.total, 2},
                        {"segments", "/cells/segments", lines.total, 2, "Int", 8},
                        {{"depth", "/cells/depth", nodes.total, 1},
                         {"velocity", "/cells/velocity", nodes.total, 1},
                         {"unit_discharge", "/cells/unit_discharge", nodes.total, 1}},
                        {}};
      xdmf_->add_step(t, {grid});
    }
  }

  void write_checkpoint() {
    ScopedPhase phase(timers_, "checkpoint");
    const auto path = checkpoint::file_name(checkpoints_, "checkpoint", p_.step);
    checkpoint::Writer w(comm_, path, {kSolver, kCheckpointFormat, p_.step, time_of(p_.step), "", 0});
    w.write_bytes("progress", std::as_bytes(std::span(&p_, 1)));
    w.write<unsigned char>("scene_keys", scene_keys_.bytes());
    const std::array<long long, 2> range{block_.first, block_.count};
    w.write<long long>("block", range);
    w.commit();
    if (comm_.is_root()) checkpoint::prune(checkpoints_, "checkpoint", s_.checkpoints.keep);
    record_.write(out_ / "run.json", timers_, fmt::format("running: checkpoint at step {}", p_.step));
    last_checkpoint_step_ = p_.step;
    log_.info("checkpoint {} written", path.filename().string());
  }


  void resume(const std::string& which) {
    const auto path = checkpoint::restart_path(comm_, checkpoints_, "checkpoint", which);
    checkpoint::Reader r(comm_, path, kSolver, kCheckpointFormat);
    const auto bytes = r.read_bytes("progress");
    if (bytes.size() != sizeof(Progress))
      throw InputError(fmt::format("checkpoint '{}' holds a progress record of {} bytes, not {}", path.string(),
                                   bytes.size(), sizeof(Progress)));
    std::memcpy(&p_, bytes.data(), sizeof p_);
    const auto where = fmt::format("checkpoint '{}'", path.string());
    checkpoint::SceneRecord::from_bytes(r.read<unsigned char>("scene_keys"), where)
        .require_same(scene_keys_, kMayChangeOnRestart, where);
    checkpoint::require_later_end(s_.t_end, r.header().time, where);
    last_checkpoint_step_ = p_.step;
    const auto range = r.read<long long>("block");
    if (range != std::vector<long long>{block_.first, block_.count})
      throw LibraryError("checkpoint block layout differs from this run's");
    record_.extra()["restarted_from"] = path.string();
    // later ones belong to the run being replaced
    checkpoint::discard_after(comm_, checkpoints_, "checkpoint", p_.step, log_);
    log_.info("restarting from {} at step {} (t = {} s)", path.filename().string(), p_.step, time_of(p_.step));
    start_outputs(true);
  }

  void finish() {
    const double q_dam = s_.width * ritter_.unit_discharge_at_dam();
    Summary summary;
    summary.set("discharge_at_dam", q_dam, "m^3/s");
    summary.set("peak_outflow", p_.peak_outflow, "m^3/s");
    summary.set("time_to_peak", p_.time_to_peak, "s");
    summary.set("outflow_volume", p_.outflow_volume, "m^3");
    summary.set("front_position", ritter_.front_position(s_.t_end), "m");
    summary.set("max_balance_error", p_.max_balance_error);
    summary.set("cells", double(s_.cells));
    mpi::collective_try(comm_, [&] {
      if (comm_.is_root()) summary.write(out_ / "summary.json");
    });
    record_.write(out_ / "run.json", timers_, "completed");
    log_.info(
        "done: discharge at the dam {:.6g} m^3/s (Ritter: 8/27 sqrt(g) h0^1.5 x width), peak outflow {:.6g} m^3/s "
        "at t = {} s, largest water-balance error {:.2e}",
        q_dam, p_.peak_outflow, p_.time_to_peak, p_.max_balance_error);
    log_.info("outputs in {}: summary.json, discharge.csv, dam_break.xmf (open in ParaView), run.json", out_.string());
  }

  mpi::Comm comm_;
  Scene s_;
  checkpoint::SceneRecord scene_keys_;  // the scene as read, kept in every checkpoint
  Logger& log_;
  RitterSolution ritter_;
  Block block_;
  RunRecord record_;
  PhaseTimers timers_;
  std::filesystem::path out_, checkpoints_;
  long long n_steps_ = 0, output_every_ = 1;
  long long last_checkpoint_step_ = -1;  // the step of the newest checkpoint of this run
  double initial_volume_ = 0.0;
  Progress p_;
  std::optional<io::CsvSeries> csv_;    // rank 0 only
  std::optional<io::XdmfSeries> xdmf_;  // rank 0 only
};

}  // namespace

int run_dam_break(const mpi::Comm& comm, const config::Config& scene, const DamBreakOptions& options, Logger& log) {
  const Scene s = read_scene(scene);
  DamBreakRun run(comm, s, checkpoint::SceneRecord(scene), options, log);
  mpi::collective_try(comm, [&] {
    if (!comm.is_root()) return;
    scene.write_effective(run.out() / "effective_config.yaml");
    log.add_file(run.out() / "log.txt");
  });
  return run.run(options.restart);
}

}  // namespace suite::demo
