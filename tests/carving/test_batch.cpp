// Seed batches: manifests, the streamed results table, failed seeds that never stop the batch,
// reruns that skip finished seeds, array shards merged in manifest order, and MPI ranks that
// give the same table as one process. Run at 1 and 2 ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "carving/batch/manifest.hpp"
#include "carving/batch/results_table.hpp"
#include "carving/batch/run_batch.hpp"
#include "carving/render/renderer.hpp"
#include "carving/render/shapes.hpp"
#include "core/io/atomic_file.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::carving {
namespace {

using testing::input_error_of;
using testing::read_file;
using testing::scratch_dir;

constexpr int kViews = 12;
constexpr double kScale = 40;  // px/mm, parallel views of 200 x 160 px

void write(const std::filesystem::path& p, const std::string& text) {
  io::write_file_atomic(p, text);
}

// A sphere photographed from kViews parallel views into `dir`.
void render_sphere(const std::filesystem::path& dir, double radius) {
  std::filesystem::create_directories(dir);
  const ParallelTurntable rig{kScale, 100, 80, kViews, 0, 2 * std::numbers::pi / kViews, 200, 160};
  const Sphere sphere(radius);
  for (int v = 0; v < kViews; ++v)
    write_png(dir / fmt::format("view_{:02d}.png", v + 1), render(sphere, rig.all_views()[v]).image);
}

constexpr const char* kProfile =
    "method: carving\n"
    "segmentation: {area_px: [200, 20000]}\n"
    "camera: {model: parallel, px_per_mm: 40, principal_point: [100, 80], step: 30 deg}\n"
    "carving: {resolution: 96, mesh_resolution: 48}\n";

// Three seeds that measure, one missing folder, one image with no seed in it.
std::filesystem::path make_batch(const std::filesystem::path& dir) {
  render_sphere(dir / "s1", 1.0);
  render_sphere(dir / "s2", 1.4);
  render_sphere(dir / "s3", 0.8);
  render_sphere(dir / "blank", 1.0);
  write_png(dir / "blank" / "view_05.png", cv::Mat(160, 200, CV_8UC3, cv::Scalar(38, 15, 10)));
  write(dir / "profile.yaml", kProfile);
  write(dir / "manifest.csv",
        "id,images,weight_mg\n"
        "s1,s1,4.2\n"
        "gone,no_such_folder,\n"
        "s2,s2,\n"
        "blank,blank,\n"
        "s3,s3,2.0\n");
  return dir / "manifest.csv";
}

// Visual hull of a sphere from 12 parallel views: (4N/3) tan(pi/N) r^3 (N = 12 sides), +2.3% over
// the sphere; the tolerance covers pixels (25-56 px radius: ~1%) and 96 voxels across the seed.
constexpr double kHullTolerance = 0.02;
double hull_volume(double r) {
  return 4.0 * 12 / 3 * std::tan(std::numbers::pi / 12) * r * r * r;
}

TEST(SeedBatch, GoodSeedsAreMeasuredAndBadOnesFailTheirRowOnly) {
  const mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = scratch_dir(world);
  if (world.is_root()) make_batch(dir);
  world.barrier();
  Logger log(world, "test", {LogLevel::warn});
  const auto counts = run_batch({dir / "manifest.csv", dir / "out", dir / "profile.yaml", false, 0, 0, &world}, log);
  if (!world.is_root()) return;
  EXPECT_EQ(counts.seeds, 5u);
  EXPECT_EQ(counts.measured, 5u);
  EXPECT_EQ(counts.failed, 2u);
  const auto rows = read_results(dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 5u);
  const std::vector<std::string> order = {"s1", "gone", "s2", "blank", "s3"};  // the manifest's
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].id, order[i]);
  EXPECT_TRUE(rows[0].ok) << rows[0].message;
  EXPECT_NEAR(rows[0].volume_mm3 / hull_volume(1.0) - 1, 0, kHullTolerance);
  EXPECT_NEAR(rows[0].density_mg_mm3, 4.2 / rows[0].volume_mm3, 1e-4);
  EXPECT_NEAR(rows[2].volume_mm3 / hull_volume(1.4) - 1, 0, kHullTolerance);
  EXPECT_TRUE(std::isnan(rows[2].density_mg_mm3)) << "no weight, no density";
  // The hull's cross-section is a 12-gon around the 1.6 mm circle: its extent along any axis lies
  // between the diameter and the diameter / cos(15 deg), plus about two voxels of the 96 across.
  EXPECT_GT(rows[4].length_mm, 1.6 - 0.01);
  EXPECT_LT(rows[4].length_mm, 1.6 / std::cos(std::numbers::pi / 12) + 2 * 1.6 * 1.05 / 96);
  EXPECT_FALSE(rows[1].ok);
  EXPECT_NE(rows[1].message.find("no_such_folder"), std::string::npos) << rows[1].message;
  EXPECT_FALSE(rows[3].ok);
  EXPECT_NE(rows[3].message.find("view 5 ('view_05.png')"), std::string::npos) << rows[3].message;
  for (const char* id : {"s1", "s2", "s3"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "seeds" / id / "overlays.png")) << id;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "seeds" / id / "surface.ply")) << id;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "seeds" / id / "seed.json")) << id;
  }
}

TEST(SeedBatch, RerunSkipsFinishedSeedsAndRetriesFailedOnes) {
  const mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = scratch_dir(world);
  if (world.is_root()) make_batch(dir);
  world.barrier();
  Logger log(world, "test", {LogLevel::warn});
  BatchOptions o{dir / "manifest.csv", dir / "out", dir / "profile.yaml", false, 0, 0, &world};
  run_batch(o, log);
  const std::string first = world.is_root() ? read_file(dir / "out" / "results.csv") : "";
  // A kill mid-write leaves a torn line: it is not a row, and the seed is measured again... but
  // here every seed finished, so nothing runs.
  if (world.is_root()) std::ofstream(dir / "out" / "results.csv", std::ios::app) << "s9,carving,1.0,2";
  world.barrier();
  const auto again = run_batch(o, log);
  if (world.is_root()) {
    EXPECT_EQ(again.skipped, 5u);
    EXPECT_EQ(again.measured, 0u);
    EXPECT_EQ(read_file(dir / "out" / "results.csv"), first);
  }
  o.retry_failed = true;
  const auto retried = run_batch(o, log);
  if (world.is_root()) {
    EXPECT_EQ(retried.measured, 2u);
    EXPECT_EQ(retried.failed, 2u);
    EXPECT_EQ(read_results(dir / "out" / "results.csv").size(), 5u) << "the newest row of each seed";
  }
}

TEST(SeedBatch, ArrayShardsMergeIntoTheManifestsOrder) {
  const mpi::Comm self(MPI_COMM_SELF);
  const mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = scratch_dir(world);
  if (!world.is_root()) return;
  make_batch(dir);
  Logger log(self, "test", {LogLevel::warn});
  for (int k = 0; k < 2; ++k)
    run_batch({dir / "manifest.csv", dir / "arr", dir / "profile.yaml", false, k, 2, nullptr}, log);
  EXPECT_EQ(read_results(dir / "arr" / "results.0.csv").size(), 3u);  // seeds 0, 2, 4
  EXPECT_EQ(read_results(dir / "arr" / "results.1.csv").size(), 2u);
  merge_batch(dir / "arr");
  run_batch({dir / "manifest.csv", dir / "one", dir / "profile.yaml", false, 0, 0, nullptr}, log);
  const auto merged = read_results(dir / "arr" / "results.csv"), single = read_results(dir / "one" / "results.csv");
  ASSERT_EQ(merged.size(), single.size());
  for (std::size_t i = 0; i < merged.size(); ++i) {
    EXPECT_EQ(merged[i].id, single[i].id);
    EXPECT_EQ(merged[i].ok, single[i].ok);
    if (merged[i].ok) {
      EXPECT_EQ(merged[i].volume_mm3, single[i].volume_mm3) << merged[i].id;
    }
  }
}

// A second manifest into the same folder adds its seeds' rows to the first's; an id the folder
// holds with other images, and an id that would share another's seed folder, are refused before
// anything is measured.
TEST(SeedBatch, ASecondManifestAddsRowsAndConflictsAreRefused) {
  const mpi::Comm self(MPI_COMM_SELF);
  const mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = scratch_dir(world);
  if (!world.is_root()) return;
  make_batch(dir);
  render_sphere(dir / "s4", 1.2);
  Logger log(self, "test", {LogLevel::warn});
  const BatchOptions first{dir / "manifest.csv", dir / "out", dir / "profile.yaml", false, 0, 0, nullptr};
  run_batch(first, log);
  ASSERT_EQ(read_results(dir / "out" / "results.csv").size(), 5u);
  write(dir / "second.csv", "id,images\ns_4,s4\ns1,s1\n");
  auto second = first;
  second.manifest = dir / "second.csv";
  const auto counts = run_batch(second, log);
  EXPECT_EQ(counts.measured, 1u);
  EXPECT_EQ(counts.skipped, 1u) << "s1, the same images as before";
  const auto rows = read_results(dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 6u) << "the first manifest's rows are kept";
  EXPECT_EQ(rows.front().id, "s1");
  EXPECT_EQ(rows.back().id, "s_4");
  const std::string before = read_file(dir / "out" / "results.csv");
  write(dir / "other_images.csv", "id,images\ns1,s2\n");
  auto other = first;
  other.manifest = dir / "other_images.csv";
  EXPECT_NE(input_error_of([&] {
              run_batch(other, log);
            }).find("seed 's1': '" + (dir / "out").string() + "' already holds it"),
            std::string::npos);
  write(dir / "shared_folder.csv", "id,images\ns.4,s4\ns 4,s3\n");
  other.manifest = dir / "shared_folder.csv";
  EXPECT_NE(input_error_of([&] { run_batch(other, log); }).find("already holds seed 's_4', whose folder 's_4'"),
            std::string::npos);
  EXPECT_EQ(read_file(dir / "out" / "results.csv"), before) << "a refused batch changes nothing";
}

TEST(Manifest, MistakesAreNamed) {
  const mpi::Comm self(MPI_COMM_SELF);
  const auto dir = scratch_dir(self);
  auto error_of = [&](const std::string& text) {
    write(dir / "m.csv", text);
    return input_error_of([&] { read_manifest(dir / "m.csv"); });
  };
  EXPECT_NE(error_of("id,images,wieght_mg\na,b,1\n").find("unknown column 'wieght_mg' (did you mean 'weight_mg'?)"),
            std::string::npos);
  EXPECT_NE(error_of("id,method\na,carving\n").find("no 'images' column"), std::string::npos);
  EXPECT_NE(error_of("id,images\na,x\na,y\n").find("seed 'a' (row 2): the id appears twice"), std::string::npos);
  EXPECT_NE(error_of("id,images,method\na,x,voxels\n").find("method 'voxels'; use carving or slicing"),
            std::string::npos);
  EXPECT_NE(error_of("id,images,weight_mg\na,x,-3\n").find("weight_mg = -3 must be > 0"), std::string::npos);
  EXPECT_NE(error_of("id,images\ngraine \xC3\xA9 1,x\ngraine____1,y\n")
                .find("ids 'graine \xC3\xA9 1' and 'graine____1' would share the output folder 'graine____1'"),
            std::string::npos);
  // A spreadsheet's byte-order mark before the header is not part of the first column's name.
  write(dir / "bom.csv", "\xEF\xBB\xBFid,images\na,x\n");
  EXPECT_EQ(read_manifest(dir / "bom.csv").at(0).id, "a");
  write(dir / "ok.csv", "id,images,profile\na,x;y.png ; z.png,p.yaml\n");
  const auto seeds = read_manifest(dir / "ok.csv");
  ASSERT_EQ(seeds[0].images.size(), 3u);
  EXPECT_EQ(seeds[0].images[2], dir / "z.png");
  EXPECT_EQ(seeds[0].profile, dir / "p.yaml");
}

TEST(ResultsTable, RowsRoundTripWithQuotedMessages) {
  const mpi::Comm self(MPI_COMM_SELF);
  const auto dir = scratch_dir(self);
  SeedRow a{"a,1", "carving", 7.1, 3.5, 2.9, 39.25, 60.5, 1.1, 36, true, "touches_frame", "", 0.25, "node1"};
  SeedRow b{"b", "slicing", NAN, NAN, NAN, NAN, NAN, NAN, 2, false, "", "view 2 ('x.png'): no contour, \"really\"",
            0.5, "n"};
  {
    ResultsWriter w(dir / "r.csv");
    w.append(a);
    w.append(b);
  }
  const auto rows = read_results(dir / "r.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].id, "a,1");
  EXPECT_DOUBLE_EQ(rows[0].volume_mm3, 39.25);
  EXPECT_EQ(rows[1].message, b.message);
  EXPECT_EQ(rows[0].quality, "touches_frame");
  // A table from before the quality column reads, its rows without flags.
  write(dir / "legacy.csv",
        "id,method,length_mm,width_mm,thickness_mm,volume_mm3,surface_mm2,density_mg_mm3,n_views,status,message,"
        "wall_s,host\nold,carving,1,1,1,0.5,3,,36,ok,,0.1,n\n");
  const auto legacy = read_results(dir / "legacy.csv");
  ASSERT_EQ(legacy.size(), 1u);
  EXPECT_TRUE(legacy[0].ok);
  EXPECT_EQ(legacy[0].quality, "");
  EXPECT_TRUE(std::isnan(rows[1].volume_mm3));
  write(dir / "other.csv", "id,volume\nx,1\n");
  EXPECT_NE(input_error_of([&] { read_results(dir / "other.csv"); }).find("is not a seedcarve results table"),
            std::string::npos);
}

}  // namespace
}  // namespace suite::carving
