// The OpenFOAM case of a scene, checked with the real OpenFOAM programs (blockMesh, checkMesh,
// subsetMesh, topoSet, setFields) and read back with the coupling's own reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/config/config.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/foam_erosion_fem/case/dam_cells.hpp"
#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"
#include "solvers/foam_erosion_fem/run/breach_comparison.hpp"
#include "solvers/foam_erosion_fem/run/prepare_case.hpp"
#include "solvers/foam_erosion_fem/run/foam_runner.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"
#include "tests/support/test_dirs.hpp"

namespace fs = std::filesystem;
using namespace suite::foam_erosion;

namespace {

const fs::path kScene = fs::path(SUITE_SOURCE_DIR) / "solvers/foam_erosion_fem/scenes/lab_embankment.yaml";

FoamScene scene_with(const std::vector<std::string>& overrides = {}) {
  auto cfg = suite::config::Config::from_file(kScene, overrides);
  auto s = FoamScene::read(cfg.root());
  cfg.finish();
  return s;
}

// This test's own scratch folder (tests/support/test_dirs.hpp), emptied first.
fs::path fresh_dir() { return suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF)); }

double distance_to_curve(const SectionLayout& L, const Eigen::Vector2d& p) {
  double nearest = 1e300;
  for (std::size_t i = 0; i + 1 < L.dam_nodes.size(); ++i) {
    const Eigen::Vector2d a = L.dam_nodes[i], b = L.dam_nodes[i + 1];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (a + t * (b - a) - p).norm());
  }
  return nearest;
}

}  // namespace

// The breach model's run beside the coupled one sees the same dam, inflow and pool, the kd of the
// accelerated erosion (kd x morphological factor), and the 2D section's upstream storage: at
// every level the table's volume is the water area upstream of the dam (floor plus the wedge on
// the upstream face) times the crest length, within the error of interpolating that quadratic
// linearly between rows dz apart (slope x dz^2 / 8 per metre of crest).
TEST(BreachComparison, SameDamAndInflowAndTheSectionsUpstreamStorage) {
  const auto s = scene_with();
  const auto b = breach_scene_for(s);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->dam.height, s.dam.height);
  EXPECT_EQ(b->dam.crest_width, s.dam.crest_width);
  EXPECT_EQ(b->dam.downstream_slope, s.dam.downstream_slope);
  EXPECT_DOUBLE_EQ(b->soil.kd, s.soil.kd * s.coupling.morphological_factor);
  EXPECT_EQ(b->reservoir.initial_level, s.initial_level);
  EXPECT_EQ(b->time.end, s.time.end);
  for (double t : {0.0, 1.0, 3.5}) EXPECT_EQ(b->inflow(t), s.inflow(t));
  const double L = s.domain.upstream_length, m = s.dam.upstream_slope, H = s.dam.height;
  const double dz = s.domain.height / 64, tol = m * dz * dz / 8 * s.dam.crest_length + 1e-15;
  for (double d : {0.0, 0.05, 0.1234, H, H + 0.07}) {
    const double area = d <= H ? L * d + 0.5 * m * d * d : L * d + 0.5 * m * H * H + m * H * (d - H);
    EXPECT_NEAR(b->reservoir.storage.volume(s.dam.foundation + d), area * s.dam.crest_length, tol) << "depth " << d;
  }
  // Without s_u and the unit weight (the headcut's) there is no comparison.
  auto no_su = s;
  no_su.soil.undrained_shear_strength.reset();
  EXPECT_FALSE(breach_scene_for(no_su).has_value());
}

// The dam nodes lie on the trapezoid, no element is longer than the cell size, and the three
// corners (toe, crest edges, toe) are nodes, so the discharge sections sit on mesh lines.
TEST(SectionLayout, NodesFollowTheTrapezoidWithinTheCellSize) {
  const auto s = scene_with();
  const auto L = SectionLayout::initial(s);
  const double h = s.mesh.cell_size;
  ASSERT_GE(L.dam_nodes.size(), 3u);
  for (std::size_t i = 0; i + 1 < L.dam_nodes.size(); ++i) {
    EXPECT_LE((L.dam_nodes[i + 1] - L.dam_nodes[i]).norm(), h * (1 + 1e-12));
    EXPECT_GT(L.dam_nodes[i + 1].x(), L.dam_nodes[i].x());
  }
  const double x_toe = s.domain.upstream_length;
  for (const auto& p : L.dam_nodes) {
    const double x = p.x() - x_toe;
    const double expected = std::min({s.dam.crest(), s.dam.foundation + x / s.dam.upstream_slope,
                                      s.dam.foundation + (L.x_toe_section - p.x()) / s.dam.downstream_slope});
    EXPECT_NEAR(p.y(), expected, 1e-12);
  }
  // The crest edge and the toe, where discharge is measured, are mesh lines: ends of x blocks.
  auto is_block_edge = [&](double x) {
    return std::any_of(L.x_blocks.begin(), L.x_blocks.end(), [&](const auto& b) { return std::abs(b.x1 - x) < 1e-12; });
  };
  EXPECT_TRUE(is_block_edge(L.x_crest_section));
  EXPECT_TRUE(is_block_edge(L.x_toe_section));
  for (std::size_t i = 0; i + 1 < L.x_blocks.size(); ++i) EXPECT_EQ(L.x_blocks[i].x1, L.x_blocks[i + 1].x0);
  EXPECT_EQ(L.x_blocks.front().x0, L.x_inlet);
  EXPECT_EQ(L.x_blocks.back().x1, L.x_outlet);
  EXPECT_NEAR(L.x_outlet - L.x_toe_section, s.domain.downstream_length, 1e-12);
  // The trapezoid's area, (crest width + base width) / 2 x height.
  const double base = s.dam.crest_width + (s.dam.upstream_slope + s.dam.downstream_slope) * s.dam.height;
  EXPECT_NEAR(L.dam_area(), 0.5 * (s.dam.crest_width + base) * s.dam.height, 1e-12);
}

// blockMesh builds the background the layout describes; subsetMesh cuts out exactly the cells
// whose centre is inside the dam (so the cut area is the dam's area to within half a cell along
// its perimeter); checkMesh passes the result; the staircase dam faces hug the FEM curve.
TEST(FoamCase, StaircaseMeshCutsTheDamOutOfTheBackground) {
  const auto s = scene_with({"mesh.cell_size=0.02 m", "mesh.far_cell_size=0.06 m"});
  const auto dir = fresh_dir();
  FoamRunner runner(dir / "case", dir / "logs");
  const auto prepared = prepare_case(s, runner, s.time.end);
  const auto& L = prepared.layout;
  const auto mesh = PolyMesh::read(dir / "case/constant/polyMesh");
  EXPECT_EQ(mesh.cells(), prepared.mesh.cells);
  EXPECT_LT(prepared.mesh.cells, prepared.mesh.background_cells);

  // Every flow cell is outside the dam; the cut cells (all in the uniform dam blocks) add up to
  // the dam's area within half a cell along its perimeter.
  const auto centres = mesh.cell_centres();
  for (const auto& c : centres) EXPECT_FALSE(inside_dam(L, {c.x(), c.y()})) << c.transpose();
  // subsetMesh keeps the background order: flow cell j is background cell fluid[j] (the re-mesh
  // relies on it to find the cells erosion opens).
  ASSERT_EQ(centres.size(), prepared.mesh.fluid.size());
  for (std::size_t j = 0; j < centres.size(); ++j)
    ASSERT_LT((centres[j] - prepared.mesh.background_centres[static_cast<std::size_t>(prepared.mesh.fluid[j])]).norm(),
              1e-12)
        << "flow cell " << j;
  const auto& dam_block = L.x_blocks[1];
  const double dx = (dam_block.x1 - dam_block.x0) / dam_block.cells, dy = (L.top - L.floor) / L.vertical_cells;
  const double cut_area = static_cast<double>(prepared.mesh.background_cells - prepared.mesh.cells) * dx * dy;
  double perimeter = 0.0;
  for (std::size_t i = 0; i + 1 < L.dam_nodes.size(); ++i) perimeter += (L.dam_nodes[i + 1] - L.dam_nodes[i]).norm();
  EXPECT_NEAR(cut_area, L.dam_area(), 0.5 * perimeter * std::max(dx, dy));

  // The dam patch: faces within a cell of the curve, outward normals (out of the flow, into the
  // dam) axis-aligned, a staircase about as long as the curve and at most its L1 length.
  const auto& dam = mesh.patch("dam");
  ASSERT_EQ(dam.faces, prepared.mesh.dam_faces);
  double stair_length = 0.0, l1_length = 0.0;
  for (std::size_t i = 0; i + 1 < L.dam_nodes.size(); ++i)
    l1_length += (L.dam_nodes[i + 1] - L.dam_nodes[i]).lpNorm<1>();
  for (int f = dam.start_face; f < dam.start_face + dam.faces; ++f) {
    const Eigen::Vector3d c = mesh.face_centre(f), n = mesh.face_area(f).normalized();
    const double nearest = distance_to_curve(L, {c.x(), c.y()});
    EXPECT_LE(nearest, std::max(dx, dy)) << "dam face " << f;
    EXPECT_NEAR(std::abs(n.x()) + std::abs(n.y()), 1.0, 1e-12);
    // Half a cell along the normal is the centre of the cut cell behind the face: in the dam.
    // (A centre on the curve itself may fall either way.)
    const double half = 0.5 * (std::abs(n.x()) * dx + std::abs(n.y()) * dy);
    const Eigen::Vector2d behind = Eigen::Vector2d(c.x(), c.y()) + half * Eigen::Vector2d(n.x(), n.y());
    if (distance_to_curve(L, behind) > 1e-9) {
      EXPECT_TRUE(inside_dam(L, behind))
          << "dam face " << f << " at " << c.transpose() << " normal " << n.transpose() << " points out of the dam";
    }
    stair_length += mesh.face_area(f).norm() / L.thickness;
  }
  EXPECT_GT(stair_length, 0.9 * perimeter);
  EXPECT_LT(stair_length, 1.1 * l1_length);

  // The inlet faces under the reservoir level start wet (setFields), the others dry.
  const auto& inlet = mesh.patch("inlet");
  const auto alpha = read_patch_value(dir / "case/0/alpha.water", "inlet", 1, static_cast<std::size_t>(inlet.faces));
  for (int f = 0; f < inlet.faces; ++f) {
    const double yc = mesh.face_centre(inlet.start_face + f).y();
    EXPECT_EQ(alpha.at(static_cast<std::size_t>(f)), yc < s.initial_level ? 1.0 : 0.0) << "inlet face at y = " << yc;
  }
  // Internal field: one value per cell.
  EXPECT_EQ(read_internal_field(dir / "case/0/alpha.water", 1, static_cast<std::size_t>(mesh.cells())).size(),
            static_cast<std::size_t>(mesh.cells()));
  fs::remove_all(dir);
}

// A failing OpenFOAM program is reported with its name, the reason, its log and the case.
TEST(FoamRunner, FailureNamesProgramLogAndCase) {
  const auto dir = fresh_dir();
  fs::create_directories(dir / "case/system");
  FoamRunner runner(dir / "case", dir / "logs");
  try {
    runner.run("blockMesh");
    FAIL() << "blockMesh without a blockMeshDict should fail";
  } catch (const FoamRunError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("blockMesh failed"), std::string::npos) << m;
    EXPECT_NE(m.find((dir / "logs/log.blockMesh").string()), std::string::npos) << m;
    EXPECT_NE(m.find((dir / "case").string()), std::string::npos) << m;
    EXPECT_NE(m.find("FOAM FATAL"), std::string::npos) << m;  // quoted from the log tail
  }
  fs::remove_all(dir);
}
