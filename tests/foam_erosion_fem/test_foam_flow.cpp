// Flows run with the real interFoam (Debian's OpenFOAM v1912) and checked against closed forms
// and conservation: the wall shear of laminar flow between plates, the discharge of a steady
// overflow of the lab embankment with the inlet following a hydrograph table, and the coupled
// erosion loop with its re-meshing.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/foam_erosion_fem/case/case_writer.hpp"
#include "solvers/foam_erosion_fem/case/foam_file.hpp"
#include "solvers/foam_erosion_fem/coupling/discharge.hpp"
#include "solvers/foam_erosion_fem/coupling/wall_shear.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"
#include "solvers/foam_erosion_fem/run/coupled_loop.hpp"
#include "solvers/foam_erosion_fem/run/prepare_case.hpp"
#include "solvers/foam_erosion_fem/run/foam_runner.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"
#include "tests/support/test_dirs.hpp"

namespace fs = std::filesystem;
using namespace suite::foam_erosion;

namespace {

const fs::path kScene = fs::path(SUITE_SOURCE_DIR) / "solvers/foam_erosion_fem/scenes/lab_embankment.yaml";

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

FoamScene scene_from_text(const std::string& yaml, const fs::path& dir, const std::vector<std::string>& overrides) {
  const fs::path file = dir / "scene.yaml";
  std::ofstream(file) << yaml;
  auto cfg = suite::config::Config::from_file(file, overrides);
  auto s = FoamScene::read(cfg.root());
  cfg.finish();
  return s;
}

// This test's own scratch folder (tests/support/test_dirs.hpp), emptied first.
fs::path fresh_dir() { return suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF)); }

std::string field(const std::string& cls, const std::string& name, const std::string& dims,
                  const std::string& internal, const std::string& patches) {
  return foam_header(cls, name, "0") + fmt::format("dimensions {};\ninternalField {};\nboundaryField\n{{\n{}"
                                                   "    frontAndBack {{ type empty; }}\n}}\n",
                                                   dims, internal, patches);
}

}  // namespace

// Plane Poiseuille flow: water of viscosity nu fills a channel of height H between two walls,
// entering with mean velocity U. Once developed the profile is u = 6 U (y/H)(1 - y/H), so the
// bed shear is tau = 6 mu U / H. The shear extraction (wallShearStress of interFoam, made
// dimensional with the water fraction of the wall cells, tangential part) must recover it within
// 5%: the first cell centre sits at H/60, where the one-sided wall gradient of the parabola is
// low by H/60 / H ~ 1.7%.
TEST(FoamFlow, LaminarPlatesWallShearIsSixMuUOverH) {
  const auto dir = fresh_dir();
  const fs::path case_dir = dir / "case";
  const double H = 0.02, length = 0.2, U = 0.1, thickness = 0.002;
  auto cfg = suite::config::Config::from_file(kScene, {});
  auto s = FoamScene::read(cfg.root());
  cfg.finish();
  s.gravity = 0.0;
  s.flow.turbulence = "laminar";
  s.flow.water = {1000.0, 1.0e-4};  // Re = U H / nu = 20: developed within 0.05 Re H = 0.02 m
  s.flow.surface_tension = 0.0;
  write_constant(s, case_dir);
  write_numerics(case_dir);
  write_case_file(case_dir, "system/blockMeshDict",
                  foam_header("dictionary", "blockMeshDict", "system") +
                      fmt::format("scale 1;\nvertices ((0 0 0) ({0} 0 0) ({0} {1} 0) (0 {1} 0) (0 0 {2}) ({0} 0 {2}) "
                                  "({0} {1} {2}) (0 {1} {2}));\n"
                                  "blocks (hex (0 1 2 3 4 5 6 7) (60 30 1) simpleGrading (1 1 1));\nedges ();\n"
                                  "boundary (\n inlet {{ type patch; faces ((0 4 7 3)); }}\n"
                                  " outlet {{ type patch; faces ((1 2 6 5)); }}\n"
                                  " dam {{ type wall; faces ((0 1 5 4)); }}\n"
                                  " lid {{ type wall; faces ((3 7 6 2)); }}\n"
                                  " frontAndBack {{ type empty; faces ((0 3 2 1) (4 5 6 7)); }}\n);\n",
                                  length, H, thickness));
  write_case_file(case_dir, "system/controlDict",
                  foam_header("dictionary", "controlDict", "system") +
                      "application interFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 6;\n"
                      "deltaT 0.005;\nwriteControl adjustableRunTime;\nwriteInterval 6;\nwriteFormat ascii;\n"
                      "writePrecision 12;\ntimeFormat general;\nadjustTimeStep yes;\nmaxCo 0.8;\nmaxAlphaCo 0.8;\n"
                      "maxDeltaT 0.05;\nfunctions\n{\n    wallShearStress\n    {\n        type wallShearStress;\n"
                      "        libs (\"libfieldFunctionObjects.so\");\n        patches (dam);\n"
                      "        writeControl writeTime;\n    }\n}\n");
  const std::string walls = "    dam { type noSlip; }\n    lid { type noSlip; }\n";
  write_case_file(case_dir, "0/U",
                  field("volVectorField", "U", "[0 1 -1 0 0 0 0]", "uniform (0 0 0)",
                        fmt::format("    inlet {{ type fixedValue; value uniform ({} 0 0); }}\n"
                                    "    outlet {{ type zeroGradient; }}\n{}",
                                    U, walls)));
  write_case_file(case_dir, "0/alpha.water",
                  field("volScalarField", "alpha.water", "[0 0 0 0 0 0 0]", "uniform 1",
                        "    inlet { type fixedValue; value uniform 1; }\n    outlet { type zeroGradient; }\n"
                        "    dam { type zeroGradient; }\n    lid { type zeroGradient; }\n"));
  write_case_file(case_dir, "0/p_rgh",
                  field("volScalarField", "p_rgh", "[1 -1 -2 0 0 0 0]", "uniform 0",
                        "    inlet { type zeroGradient; }\n    outlet { type fixedValue; value uniform 0; }\n"
                        "    dam { type zeroGradient; }\n    lid { type zeroGradient; }\n"));
  FoamRunner runner(case_dir, dir / "logs");
  runner.run("blockMesh");
  runner.run("interFoam");

  const auto faces = read_wall_shear(case_dir, latest_time_directory(case_dir), "dam", s.flow.water, s.flow.air);
  ASSERT_EQ(faces.size(), 60u);
  const double expected = 6.0 * s.flow.water.density * s.flow.water.viscosity * U / H;  // 3 Pa
  int developed = 0;
  double worst = 0.0;
  for (const auto& f : faces) {
    EXPECT_NEAR(f.length, length / 60, 1e-12);
    EXPECT_NEAR(f.alpha, 1.0, 1e-6);
    if (f.centre.x() < 0.5 * length || f.centre.x() > 0.9 * length) continue;
    EXPECT_NEAR(f.shear, expected, 0.05 * expected) << "face at x = " << f.centre.x();
    worst = std::max(worst, std::abs(f.shear / expected - 1.0));
    ++developed;
  }
  std::printf("plate shear: expected %.4f Pa, largest relative error on developed faces %.4f\n", expected, worst);
  EXPECT_EQ(developed, 24);
  // Mapped onto a curve of 10 elements along the plate: every element gets its faces' mean.
  std::vector<Eigen::Vector2d> nodes;
  for (int i = 0; i <= 10; ++i) nodes.emplace_back(length * i / 10, 0.0);
  const auto on_elements = shear_on_elements(nodes, faces);
  for (int e = 5; e < 9; ++e) EXPECT_NEAR(on_elements[static_cast<std::size_t>(e)], expected, 0.05 * expected);
  fs::remove_all(dir);
}

// The lab embankment overtopped by q = 0.03 m^2/s after a one-second flood wave on top of it
// (a hydrograph table). The inlet must impose the table at every time step, and once the
// reservoir has settled the water discharge at the crest, the toe and the outlet must equal the
// inflow within 2% (mass conservation of a steady overflow). The reservoir starts at the
// broad-crested weir level for that discharge, crest + 1.5 (q^2/g)^(1/3) = 0.368 m.
TEST(FoamFlow, SteadyOverflowDischargeMatchesTheInflowAndTheInletFollowsTheTable) {
  const auto dir = fresh_dir();
  std::string yaml = slurp(kScene);
  const auto at = yaml.find("inflow:");
  const auto end = yaml.find("domain:");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, end - at,
               "inflow:\n  type: table\n  table: [[0 s, 0.03 m^3/s], [0.5 s, 0.036 m^3/s], [1 s, 0.03 m^3/s]]\n");
  const auto s = scene_from_text(yaml, dir, {"reservoir.initial_level=0.368 m", "time.end=6 s",
                                             "coupling.interval=6 s", "time.write_interval=6 s"});
  FoamRunner runner(dir / "case", dir / "logs");
  const auto prepared = prepare_case(s, runner, s.time.end);
  const auto flow = runner.run("interFoam");
  EXPECT_LE(flow.max_courant, 1.0);

  const double per_slab = prepared.layout.thickness / s.dam.crest_length;  // slab discharge per total Q
  const auto inlet = read_discharge(runner.case_dir(), "inlet");
  ASSERT_GT(inlet.time.size(), 100u);
  for (std::size_t i = 0; i < inlet.time.size(); ++i)
    ASSERT_NEAR(-inlet.mixture[i], s.inflow(inlet.time[i]) * per_slab, 1e-9 * per_slab) << "t = " << inlet.time[i];
  const double q = 0.03 * per_slab;
  for (const char* section : {"crest", "toe", "outlet"}) {
    const auto d = read_discharge(runner.case_dir(), section);
    const double mean = time_mean(d.time, d.water, 5.0, 6.0);
    EXPECT_NEAR(mean, q, 0.02 * q) << section;
    std::printf("%s discharge over t = 5..6 s: %.5f of the inflow\n", section, mean / q);
  }
  fs::remove_all(dir);
}

// The coupled loop on the lab embankment with a strong morphological factor (1000), two coupling
// steps of 0.5 s. Checks:
//  - the eroded area of the steps adds up to the dam's lost cross-section (exact polygon areas);
//  - erosion is deepest where the overflow is fastest, on the crest or the downstream slope, not
//    on the upstream face under the slow reservoir;
//  - each re-mesh passes checkMesh (remesh_case requires it) and the map neither loses nor
//    invents water: the water volume after it is the volume before it plus the water of the cells
//    the erosion opened, which lie under the overflow and take the water fraction of their
//    nearest old cell: more than half of their volume, at most all of it;
//  - the discharge record runs on across the re-meshes up to the end time.
TEST(FoamFlow, CoupledLoopErodesTheCrestAndRemeshesWithoutLosingWater) {
  const auto dir = fresh_dir();
  const auto s = scene_from_text(slurp(kScene), dir,
                                 {"reservoir.initial_level=0.368 m", "time.end=1 s", "coupling.interval=0.5 s",
                                  "coupling.morphological_factor=1000"});
  FoamRunner runner(dir / "case", dir / "logs");
  auto prepared = prepare_case(s, runner, s.time.end);
  const SectionLayout initial = prepared.layout;
  const suite::mpi::Comm self(MPI_COMM_SELF);
  suite::Logger log(self, "test", {suite::LogLevel::warn});
  suite::PhaseTimers timers;
  const auto r = run_coupled(s, runner, prepared, dir, log, timers);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  EXPECT_EQ(r.erosion_steps, 2);
  ASSERT_GE(r.remeshes, 1);
  EXPECT_GT(r.eroded_area, 0.0);
  EXPECT_NEAR(initial.dam_area() - prepared.layout.dam_area(), r.eroded_area, 1e-9 + 1e-6 * r.eroded_area);

  std::size_t deepest = 0;
  double depth = 0.0;
  for (std::size_t i = 0; i < initial.dam_nodes.size(); ++i) {
    const double d = (prepared.layout.dam_nodes[i] - initial.dam_nodes[i]).norm();
    if (d > depth) depth = d, deepest = i;
  }
  const double x_crest_up = s.domain.upstream_length + s.dam.upstream_slope * s.dam.height;
  EXPECT_GE(initial.dam_nodes[deepest].x(), x_crest_up) << "deepest erosion at x = " << initial.dam_nodes[deepest].x();

  // Water before and after the first re-mesh, at the same time.
  const auto water = [](const fs::path& case_dir, const fs::path& time_dir) {
    const auto mesh = PolyMesh::read(case_dir / "constant/polyMesh");
    const auto volumes = mesh.cell_volumes();
    const auto alpha = read_internal_field(time_dir / "alpha.water", 1, volumes.size());
    double sum = 0.0;
    for (std::size_t c = 0; c < volumes.size(); ++c) sum += alpha.at(c) * volumes[c];
    return std::pair<double, long long>(sum, mesh.cells());
  };
  const fs::path before_case = dir / "cases/segment_000";
  const fs::path after_case = r.remeshes > 1 ? dir / "cases/segment_001" : dir / "case";
  const fs::path t_map = latest_time_directory(before_case);
  const auto [w_before, cells_before] = water(before_case, t_map);
  const auto [w_after, cells_after] = water(after_case, after_case / t_map.filename());
  // The opened cells are cells of the uniform dam blocks.
  const auto& block = initial.x_blocks[1];
  const double cell_volume = (block.x1 - block.x0) / block.cells * (initial.top - initial.floor) /
                             initial.vertical_cells * initial.thickness;
  const double opened = static_cast<double>(cells_after - cells_before) * cell_volume;
  EXPECT_GT(cells_after, cells_before);
  std::printf("re-mesh at t = %s s: %lld -> %lld cells, water %.6e -> %.6e m^3 (the opened cells hold %.3e)\n",
              t_map.filename().c_str(), cells_before, cells_after, w_before, w_after, opened);
  EXPECT_GE(w_after - w_before, 0.5 * opened);
  EXPECT_LE(w_after - w_before, opened + 1e-9 * w_before);

  const auto inlet = read_discharge(runner.case_dir(), "inlet");
  EXPECT_NEAR(inlet.time.back(), 1.0, 1e-9);
  for (std::size_t i = 1; i < inlet.time.size(); ++i) ASSERT_LE(inlet.time[i] - inlet.time[i - 1], s.time.max_dt + 1e-12);
  fs::remove_all(dir);
}
