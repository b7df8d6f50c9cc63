// The OpenFOAM case of a scene, checked with the real OpenFOAM programs (blockMesh, checkMesh,
// topoSet, setFields) and read back with the coupling's own reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/config/config.hpp"
#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/foam_io/foam_reader.hpp"
#include "solvers/foam_erosion_fem/io/prepare_case.hpp"
#include "solvers/foam_erosion_fem/runner/foam_runner.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

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

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("foam_case_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

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
  auto has_node_at = [&](double x) {
    return std::any_of(L.dam_nodes.begin(), L.dam_nodes.end(), [&](const auto& p) { return std::abs(p.x() - x) < 1e-12; });
  };
  EXPECT_TRUE(has_node_at(L.x_crest_section));
  EXPECT_TRUE(has_node_at(L.x_toe_section));
  EXPECT_NEAR(L.x_outlet - L.x_toe_section, s.domain.downstream_length, 1e-12);
}

// blockMesh builds the mesh the layout describes, checkMesh passes it, and every dam face is one
// FEM element: its two front points are the element's two nodes, in node order.
TEST(FoamCase, MeshMatchesTheLayoutAndDamFacesAreFemElements) {
  const auto s = scene_with({"mesh.cell_size=0.02 m", "mesh.far_cell_size=0.06 m"});
  const auto dir = fresh_dir("mesh");
  FoamRunner runner(dir / "case", dir / "logs");
  const auto prepared = prepare_case(s, runner, s.time.end);
  const auto& L = prepared.layout;
  const auto mesh = PolyMesh::read(dir / "case/constant/polyMesh");
  EXPECT_EQ(mesh.cells(), L.cells());

  const auto& dam = mesh.patch("dam");
  const int elements = static_cast<int>(L.dam_nodes.size()) - 1;
  ASSERT_EQ(dam.faces, elements);
  for (int e = 0; e < elements; ++e) {
    std::vector<Eigen::Vector2d> front;
    for (int p : mesh.faces[static_cast<std::size_t>(dam.start_face + e)])
      if (std::abs(mesh.points[static_cast<std::size_t>(p)].z()) < 1e-12)
        front.emplace_back(mesh.points[static_cast<std::size_t>(p)].x(), mesh.points[static_cast<std::size_t>(p)].y());
    ASSERT_EQ(front.size(), 2u);
    std::sort(front.begin(), front.end(), [](const auto& a, const auto& b) { return a.x() < b.x(); });
    EXPECT_LT((front[0] - L.dam_nodes[static_cast<std::size_t>(e)]).norm(), 1e-9) << "face " << e;
    EXPECT_LT((front[1] - L.dam_nodes[static_cast<std::size_t>(e) + 1]).norm(), 1e-9) << "face " << e;
  }
  // A point field's dam values come in meshPoints order: two points (front, back) per node.
  const auto order = mesh.patch_mesh_points("dam");
  EXPECT_EQ(order.size(), 2 * L.dam_nodes.size());
  EXPECT_EQ(std::set<int>(order.begin(), order.end()).size(), order.size());

  // The inlet faces under the reservoir level start wet (setFields), the others dry.
  const auto& inlet = mesh.patch("inlet");
  const auto alpha = read_patch_value(dir / "case/0/alpha.water", "inlet", 1, static_cast<std::size_t>(inlet.faces));
  for (int f = 0; f < inlet.faces; ++f) {
    double yc = 0;
    const auto& face = mesh.faces[static_cast<std::size_t>(inlet.start_face + f)];
    for (int p : face) yc += mesh.points[static_cast<std::size_t>(p)].y() / static_cast<double>(face.size());
    EXPECT_EQ(alpha.at(static_cast<std::size_t>(f)), yc < s.initial_level ? 1.0 : 0.0) << "inlet face at y = " << yc;
  }
  // Internal field: one value per cell.
  EXPECT_EQ(read_internal_field(dir / "case/0/alpha.water", 1, static_cast<std::size_t>(mesh.cells())).size(),
            static_cast<std::size_t>(mesh.cells()));
  fs::remove_all(dir);
}

// The dam patch entry of a point field can be rewritten (the erosion step's displacement) and
// read back, and the rest of the file still reads.
TEST(FoamCase, PatchEntryRewriteRoundTrips) {
  const auto s = scene_with({"mesh.cell_size=0.02 m"});
  const auto dir = fresh_dir("patch");
  FoamRunner runner(dir / "case", dir / "logs");
  prepare_case(s, runner, s.time.end);
  const auto mesh = PolyMesh::read(dir / "case/constant/polyMesh");
  const auto points = mesh.patch_mesh_points("dam");
  std::string entry = "        type            fixedValue;\n        value           nonuniform List<vector> " +
                      std::to_string(points.size()) + "\n(\n";
  for (std::size_t i = 0; i < points.size(); ++i) entry += "(0 " + std::to_string(-1e-3 * double(i)) + " 0)\n";
  entry += ");\n";
  const auto file = dir / "case/0/pointDisplacement";
  replace_patch_entry(file, "dam", entry);
  const auto back = read_patch_value(file, "dam", 3, points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_DOUBLE_EQ(back.at(i, 1), -1e-3 * double(i));
  const auto floor = read_patch_value(file, "floor", 3, 4);
  EXPECT_EQ(floor.at(3, 0), 0.0);
  fs::remove_all(dir);
}

// A failing OpenFOAM program is reported with its name, the reason, its log and the case.
TEST(FoamRunner, FailureNamesProgramLogAndCase) {
  const auto dir = fresh_dir("fail");
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
