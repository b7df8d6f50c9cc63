// seedcarve: seed volume, size and density from images (docs/methods/carving.md, issue 4).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "carving/app/calibrate_command.hpp"
#include "carving/batch/manifest.hpp"
#include "carving/batch/results_table.hpp"
#include "carving/batch/run_batch.hpp"
#include "carving/batch/seed_register.hpp"
#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "carving/io/carve_output.hpp"
#include "carving/measure/measure_seed.hpp"
#include "carving/measure/seed_profile.hpp"
#include "carving/render/render_scene.hpp"
#include "core/cli/subcommands.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/allocator.hpp"
#include "core/run/guarded_main.hpp"
#include "core/run/run_record.hpp"
#include "core/run/shard.hpp"

namespace {

using suite::cli::CommandSpec;
using Option = suite::cli::OptionSpec;

suite::cli::ProgramSpec program_spec() {
  const auto out = Option::text("out", "DIR", "output folder (created)");
  const auto profile = Option::text("profile", "PROFILE.yaml", "the seed profile: method, camera, segmentation");
  return {
      "seedcarve",
      "seedcarve: seed volume, size and density from images (docs/carving.md)",
      {
          CommandSpec{
              "measure",
              "one seed: IMAGES is a folder of views or the files (carving: every view in turntable order; "
              "slicing: the top view, then the side view); writes DIR/results.csv and DIR/<id>/. key.path=value "
              "overrides a profile key, e.g. carving.resolution=384, or for slicing slicing.slices=N (50) and "
              "slicing.neighbour_average=true (each column's upper and lower contour points averaged with the two "
              "columns on each side before the slices' widths are taken, the dissertation's smoothing; off by "
              "default, docs/carving.md)",
              "IMAGES...",
              1,
              -1,
              true,
              {out, Option::text("profile", "PROFILE.yaml", "the seed profile: method, camera, segmentation", true),
               Option::text("id", "ID", "the seed's id in the table (default: the first image's name)"),
               Option::number("weight", "MG", "the seed's weight, for its density")}},
          CommandSpec{"batch",
                      "every seed of the manifest (columns id,images[,method,weight_mg,profile]); rows stream to "
                      "DIR/results.csv; a rerun skips measured seeds; under mpiexec rank 0 hands seeds to the "
                      "others; --shard K/N (Slurm array task K of N) writes DIR/results.K.csv",
                      "MANIFEST.csv",
                      1,
                      1,
                      false,
                      {out, profile, Option::flag("retry-failed", "measure again the seeds that failed before"),
                       Option::text("shard", "K/N", "Slurm array task K of N: its share of the seeds")}},
          CommandSpec{"merge",
                      "DIR/results.csv from the array tasks' DIR/results.K.csv, in manifest order",
                      "DIR",
                      1,
                      1,
                      false,
                      {}},
          CommandSpec{
              "carve",
              "carve the masks and projection matrices of a carve_input.dat file (Kansas State format) as "
              "the original program does (its grid, its positions, its initial occupancy); prints the kept "
              "voxels and the volume in mm^3; with --out writes voxels.raw (the original's output layout) "
              "and voxels.h5",
              "CARVE_INPUT.dat",
              1,
              1,
              false,
              {Option::text("out", "DIR", "write voxels.raw and voxels.h5 into DIR (created)"),
               Option::count("resolution", "N",
                             "voxels along each side of the file's box, centred cells (default: the file's grid)", 1),
               Option::count("subvoxel", "S", "also the volume from S^3 sub-samples of each boundary voxel", 0)}},
          CommandSpec{"render",
                      "synthetic photographs and exact masks of an analytic seed, its true volume and a profile",
                      "SCENE.yaml",
                      1,
                      1,
                      true,
                      {Option::text("out", "DIR", "output folder (created)", true)}},
          CommandSpec{"calibrate",
                      "KIND IMAGES...: 'ball' (px/mm and camera distance from a reference ball, --diameter), "
                      "'chessboard' (K from chessboard photographs, --corners, --square) or 'axis' (the turntable "
                      "axis from one turn of a seed, --profile); writes DIR/calibration.json and DIR/camera.yaml",
                      "KIND IMAGES...",
                      1,
                      -1,
                      true,
                      {out, profile, Option::number("diameter", "MM", "ball: its diameter"),
                       Option::number("focal", "PX", "ball: the focal length, if known"),
                       Option::text("corners", "CxR", "chessboard: inner corners"),
                       Option::number("square", "MM", "chessboard: the side of a square")}},
      }};
}

struct Arguments {
  std::string command;
  std::vector<std::string> targets, overrides;
  std::string out, profile, id, log_level = "info";
  std::optional<double> weight, diameter, focal, square;
  std::string corners;
  long resolution = 0, subvoxel = 0;
  bool retry_failed = false;
  int shard_index = 0, shard_count = 0;
};

Arguments arguments_of(const suite::cli::CommandArguments& c) {
  Arguments a;
  a.command = c.command;
  a.targets = c.targets;
  a.overrides = c.overrides;
  a.out = c.text_or("out", "");
  a.profile = c.text_or("profile", "");
  a.id = c.text_or("id", "");
  a.log_level = c.log_level;
  a.weight = c.number("weight");
  a.diameter = c.number("diameter");
  a.focal = c.number("focal");
  a.square = c.number("square");
  a.corners = c.text_or("corners", "");
  a.resolution = c.count_or("resolution", 0);
  a.subvoxel = c.count_or("subvoxel", 0);
  a.retry_failed = c.has("retry-failed");
  if (c.has("shard")) {
    const suite::Shard shard = suite::parse_shard(c.text_or("shard", ""));
    a.shard_index = shard.index, a.shard_count = shard.count;
  }
  return a;
}

int measure_one(const Arguments& a, suite::Logger& log) {
  const auto profile = suite::carving::read_seed_profile(suite::config::Config::from_file(a.profile, a.overrides));
  suite::carving::SeedEntry seed;
  for (const auto& t : a.targets) seed.images.emplace_back(t);
  seed.id = a.id.empty() ? std::filesystem::path(a.targets[0]).filename().string() : a.id;
  if (seed.id.empty()) seed.id = "seed";
  seed.weight_mg = a.weight;
  const std::filesystem::path out = a.out.empty() ? "seedcarve-out" : a.out;
  // The folder's other seeds keep their rows: the register orders the table (batch/seed_register.hpp).
  const auto ids = suite::carving::register_seeds(out, {seed});
  const auto row = suite::carving::measure_seed(seed, profile, out / suite::carving::safe_folder_name(seed.id));
  std::map<std::string, suite::carving::SeedRow> rows;
  for (auto& r : suite::carving::read_results(out / "results.csv")) rows[r.id] = std::move(r);
  rows[row.id] = row;
  suite::carving::write_results(out / "results.csv", suite::carving::in_order(ids, std::move(rows)));
  suite::io::write_file_atomic(out / "profile_effective.yaml", profile.effective_yaml);
  if (!row.ok) throw suite::InputError(fmt::format("seed '{}' failed: {}", row.id, row.message));
  log.info("seed '{}' ({}, {} views): volume {:.4f} mm^3, {:.3f} x {:.3f} x {:.3f} mm{}; results in {}", row.id,
           row.method, row.n_views, row.volume_mm3, row.length_mm, row.width_mm, row.thickness_mm,
           std::isfinite(row.density_mg_mm3) ? fmt::format(", density {:.4f} mg/mm^3", row.density_mg_mm3) : "",
           (out / "results.csv").string());
  return 0;
}

// A carve_input.dat file as the original program carves it: its grid at its positions, its
// initial occupancy honoured; or, with --resolution, the box's own cells at that resolution.
int carve_file(const Arguments& a, suite::Logger& log) {
  const auto in = suite::carving::read_carve_input(a.targets[0]);
  const bool pre_cleared = std::find(in.initial.begin(), in.initial.end(), 0) != in.initial.end();
  suite::carving::VoxelGrid grid = in.original;
  if (a.resolution > 0) {
    if (pre_cleared)
      throw suite::InputError(
          fmt::format("{}: its initial occupancy clears voxels of its {} x {} x {} grid; drop "
                      "--resolution to carve that grid",
                      a.targets[0], in.grid.n[0], in.grid.n[1], in.grid.n[2]));
    grid = suite::carving::VoxelGrid::cube({0, 0, 0}, in.box_mm.maxCoeff(), static_cast<int>(a.resolution));
  }
  if (pre_cleared && a.subvoxel > 0)
    throw suite::InputError(
        fmt::format("{}: the sub-voxel volume does not honour the initial occupancy the file "
                    "clears; drop --subvoxel",
                    a.targets[0]));
  const bool bytes_needed = pre_cleared || !a.out.empty();
  const auto start = std::chrono::steady_clock::now();
  const auto r = suite::carving::carve(in.views, in.masks, grid, {static_cast<int>(a.subvoxel), bytes_needed});
  long long kept = r.voxels;
  std::vector<std::uint8_t> bytes;
  if (bytes_needed) {
    bytes = suite::carving::occupancy_bytes(r, a.resolution > 0 ? std::vector<std::uint8_t>{} : in.initial);
    kept = std::count(bytes.begin(), bytes.end(), std::uint8_t{1});
  }
  const double volume = static_cast<double>(kept) * grid.voxel_volume();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log.info(
      "{} views, {} x {} x {} voxels of {:.4g} mm{}: {} kept, {:.4f} mm^3{} in {:.3f} s", in.views.size(), grid.n[0],
      grid.n[1], grid.n[2], grid.voxel.x(),
      pre_cleared ? fmt::format(" ({} cleared beforehand)", std::count(in.initial.begin(), in.initial.end(), 0)) : "",
      kept, volume,
      a.subvoxel > 0 ? fmt::format(" ({:.4f} mm^3 with {}^3 sub-samples)", r.subvoxel_volume_mm3, a.subvoxel) : "", s);
  if (!a.out.empty()) {
    suite::carving::write_carve_output(a.out, grid, bytes);
    log.info("voxels in {} and {}", (std::filesystem::path(a.out) / "voxels.raw").string(),
             (std::filesystem::path(a.out) / "voxels.h5").string());
  }
  std::printf("%lld %.6f %.6f\n", kept, volume, a.subvoxel > 0 ? r.subvoxel_volume_mm3 : volume);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  suite::keep_freed_memory_for_reuse();
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse_command(program_spec(), argc, argv);
    if (!parsed.arguments) {
      if (world.is_root()) std::fputs((parsed.message + "\n").c_str(), parsed.exit_code ? stderr : stdout);
      return parsed.exit_code;
    }
    const Arguments a = arguments_of(*parsed.arguments);
    suite::Logger log(world, "seedcarve", {suite::parse_log_level(a.log_level), false, nullptr});
    if (a.command == "batch") {
      suite::carving::BatchOptions o;
      o.manifest = a.targets[0];
      o.out = a.out.empty() ? "seedcarve-" + o.manifest.stem().string() : a.out;
      o.profile = a.profile;
      o.retry_failed = a.retry_failed;
      o.shard_index = a.shard_index, o.shard_count = a.shard_count;
      o.comm = &world;
      const auto c = suite::carving::run_batch(o, log);
      if (world.is_root())
        log.info("{} seeds: {} measured now ({} failed), {} measured before; table {}", c.seeds, c.measured, c.failed,
                 c.skipped,
                 (o.out / (a.shard_count ? fmt::format("results.{}.csv", a.shard_index) : "results.csv")).string());
      return 0;
    }
    if (world.size() > 1)
      throw suite::InputError(fmt::format(
          "seedcarve {} runs on one process, not {}; only `seedcarve batch` uses MPI ranks", a.command, world.size()));
    if (a.command == "measure") return measure_one(a, log);
    if (a.command == "merge") {
      suite::carving::merge_batch(a.targets[0]);
      log.info("merged into {}", (std::filesystem::path(a.targets[0]) / "results.csv").string());
      return 0;
    }
    if (a.command == "carve") return carve_file(a, log);
    if (a.command == "calibrate") {
      suite::carving::CalibrateRequest r{a.targets[0],
                                         {a.targets.begin() + 1, a.targets.end()},
                                         a.profile,
                                         a.overrides,
                                         a.diameter,
                                         a.focal,
                                         a.square,
                                         a.corners,
                                         a.out.empty() ? "seedcarve-calibration" : a.out};
      suite::carving::run_calibrate(r, log);
      return 0;
    }
    if (a.command == "render") {
      const auto s = suite::carving::render_scene(suite::config::Config::from_file(a.targets[0], a.overrides), a.out);
      log.info("{} views of the {} ({:.6g} mm^3) in {}", s.views, s.shape, s.volume_mm3, a.out);
      return 0;
    }
    throw std::logic_error("seedcarve: command '" + a.command + "' has no handler");
  });
}
