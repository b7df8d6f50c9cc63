// seedcarve: seed volume, size and density from images (docs/methods/carving.md, issue 4).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "carving/app/calibrate_command.hpp"
#include "carving/batch/manifest.hpp"
#include "carving/batch/results_table.hpp"
#include "carving/batch/run_batch.hpp"
#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "carving/measure/measure_seed.hpp"
#include "carving/measure/seed_profile.hpp"
#include "carving/render/render_scene.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "core/run/shard.hpp"
#include "core/run/run_record.hpp"

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  seedcarve measure IMAGES... --profile PROFILE.yaml [--id ID] [--weight MG] [key.path=value ...] [--out DIR]\n"
    "      one seed: IMAGES is a folder of views or the files (carving: every view in turntable order;\n"
    "      slicing: the top view, then the side view); writes DIR/results.csv and DIR/<id>/\n"
    "  seedcarve batch MANIFEST.csv [--profile PROFILE.yaml] [--out DIR] [--retry-failed] [--shard K/N]\n"
    "      every seed of the manifest (columns id,images[,method,weight_mg,profile]); rows stream to\n"
    "      DIR/results.csv; a rerun skips measured seeds; under mpiexec rank 0 hands seeds to the others;\n"
    "      --shard K/N (Slurm array task K of N) writes DIR/results.K.csv\n"
    "  seedcarve merge DIR\n"
    "      DIR/results.csv from the array tasks' DIR/results.K.csv, in manifest order\n"
    "  seedcarve carve CARVE_INPUT.dat [--resolution N] [--subvoxel S]\n"
    "      carve the masks and projection matrices of a carve_input.dat file (Kansas State format)\n"
    "  seedcarve render SCENE.yaml --out DIR [key.path=value ...]\n"
    "      synthetic photographs and exact masks of an analytic seed, its true volume and a profile\n"
    "  seedcarve calibrate ball IMAGES... --diameter MM [--focal PX] [--profile P] [--out DIR]\n"
    "  seedcarve calibrate chessboard IMAGES... --corners CxR --square MM [--out DIR]\n"
    "  seedcarve calibrate axis IMAGES... --profile P [--out DIR]\n"
    "      px/mm and camera distance from a reference ball; K from chessboard photographs; the\n"
    "      turntable axis from one turn of a seed; writes DIR/calibration.json and DIR/camera.yaml\n";

struct Arguments {
  std::string command;
  std::vector<std::string> targets, overrides;
  std::string out, profile, id, log_level = "info";
  std::optional<double> weight, diameter, focal, square;
  std::string corners;
  int resolution = 0, subvoxel = 0;
  bool retry_failed = false;
  int shard_index = 0, shard_count = 0;
};

double number_argument(const std::string& flag, const std::string& value) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size()) throw suite::InputError(fmt::format("{} '{}': give a number", flag, value));
  return x;
}

Arguments parse(int argc, char** argv) {
  Arguments a;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) throw suite::InputError(std::string("no command given\n") + kUsage);
  a.command = args[0];
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& s = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw suite::InputError(s + " needs a value");
      return args[++i];
    };
    if (s == "--out") {
      a.out = value();
    } else if (s == "--profile") {
      a.profile = value();
    } else if (s == "--id") {
      a.id = value();
    } else if (s == "--weight") {
      a.weight = number_argument(s, value());
    } else if (s == "--diameter") {
      a.diameter = number_argument(s, value());
    } else if (s == "--focal") {
      a.focal = number_argument(s, value());
    } else if (s == "--square") {
      a.square = number_argument(s, value());
    } else if (s == "--corners") {
      a.corners = value();
    } else if (s == "--resolution") {
      a.resolution = static_cast<int>(number_argument(s, value()));
    } else if (s == "--subvoxel") {
      a.subvoxel = static_cast<int>(number_argument(s, value()));
    } else if (s == "--log-level") {
      a.log_level = value();
    } else if (s == "--retry-failed") {
      a.retry_failed = true;
    } else if (s == "--shard") {
      const suite::Shard shard = suite::parse_shard(value());
      a.shard_index = shard.index, a.shard_count = shard.count;
    } else if (suite::config::looks_like_override(s)) {
      a.overrides.push_back(s);
    } else if (s.rfind("--", 0) != 0) {
      a.targets.push_back(s);
    } else {
      throw suite::InputError(fmt::format("unexpected argument '{}'\n{}", s, kUsage));
    }
  }
  return a;
}

void expect_one_target(const Arguments& a, const char* what) {
  if (a.targets.size() != 1)
    throw suite::InputError(
        fmt::format("seedcarve {} needs {} (got {} arguments)\n{}", a.command, what, a.targets.size(), kUsage));
}

int measure_one(const Arguments& a, suite::Logger& log) {
  if (a.targets.empty()) throw suite::InputError(std::string("seedcarve measure needs images\n") + kUsage);
  if (a.profile.empty()) throw suite::InputError("seedcarve measure needs --profile PROFILE.yaml");
  const auto profile = suite::carving::read_seed_profile(suite::config::Config::from_file(a.profile, a.overrides));
  suite::carving::SeedEntry seed;
  for (const auto& t : a.targets) seed.images.emplace_back(t);
  seed.id = a.id.empty() ? std::filesystem::path(a.targets[0]).filename().string() : a.id;
  if (seed.id.empty()) seed.id = "seed";
  seed.weight_mg = a.weight;
  const std::filesystem::path out = a.out.empty() ? "seedcarve-out" : a.out;
  const auto row = suite::carving::measure_seed(seed, profile, out / suite::carving::safe_folder_name(seed.id));
  suite::carving::write_results(out / "results.csv", {row});
  suite::io::write_file_atomic(out / "profile_effective.yaml", profile.effective_yaml);
  if (!row.ok) throw suite::InputError(fmt::format("seed '{}' failed: {}", row.id, row.message));
  log.info("seed '{}' ({}, {} views): volume {:.4f} mm^3, {:.3f} x {:.3f} x {:.3f} mm{}; results in {}", row.id,
           row.method, row.n_views, row.volume_mm3, row.length_mm, row.width_mm, row.thickness_mm,
           std::isfinite(row.density_mg_mm3) ? fmt::format(", density {:.4f} mg/mm^3", row.density_mg_mm3) : "",
           (out / "results.csv").string());
  return 0;
}

int carve_file(const Arguments& a, suite::Logger& log) {
  expect_one_target(a, "one carve_input.dat file");
  const auto in = suite::carving::read_carve_input(a.targets[0]);
  suite::carving::VoxelGrid grid = in.grid;
  if (a.resolution > 0) grid = suite::carving::VoxelGrid::cube({0, 0, 0}, in.box_mm.maxCoeff(), a.resolution);
  const auto start = std::chrono::steady_clock::now();
  const auto r = suite::carving::carve(in.views, in.masks, grid, {a.subvoxel, false});
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log.info("{} views, {} x {} x {} voxels of {:.4g} mm: {} kept, {:.4f} mm^3{} in {:.3f} s", in.views.size(), grid.n[0],
           grid.n[1], grid.n[2], grid.voxel.x(), r.voxels, r.volume_mm3,
           a.subvoxel > 0 ? fmt::format(" ({:.4f} mm^3 with {}^3 sub-samples)", r.subvoxel_volume_mm3, a.subvoxel) : "",
           s);
  std::printf("%lld %.6f %.6f\n", r.voxels, r.volume_mm3, r.subvoxel_volume_mm3);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
      if (world.is_root()) std::fputs(kUsage, stdout);
      return 0;
    }
    const Arguments a = parse(argc, argv);
    suite::Logger log(world, "seedcarve", {suite::parse_log_level(a.log_level), false, nullptr});
    if (a.command == "batch") {
      expect_one_target(a, "one manifest");
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
      expect_one_target(a, "the batch folder");
      suite::carving::merge_batch(a.targets[0]);
      log.info("merged into {}", (std::filesystem::path(a.targets[0]) / "results.csv").string());
      return 0;
    }
    if (a.command == "carve") return carve_file(a, log);
    if (a.command == "calibrate") {
      if (a.targets.empty()) throw suite::InputError(std::string("seedcarve calibrate needs ball, chessboard or axis\n") + kUsage);
      suite::carving::CalibrateRequest r{a.targets[0], {a.targets.begin() + 1, a.targets.end()}, a.profile, a.overrides,
                                         a.diameter, a.focal, a.square, a.corners,
                                         a.out.empty() ? "seedcarve-calibration" : a.out};
      suite::carving::run_calibrate(r, log);
      return 0;
    }
    if (a.command == "render") {
      expect_one_target(a, "one scene file");
      if (a.out.empty()) throw suite::InputError("seedcarve render needs --out DIR");
      const auto s = suite::carving::render_scene(suite::config::Config::from_file(a.targets[0], a.overrides), a.out);
      log.info("{} views of the {} ({:.6g} mm^3) in {}", s.views, s.shape, s.volume_mm3, a.out);
      return 0;
    }
    throw suite::InputError(fmt::format("unknown command '{}'\n{}", a.command, kUsage));
  });
}
