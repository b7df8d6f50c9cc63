#include "solvers/foam_erosion_fem/case/block_mesh_dict.hpp"

#include <fmt/format.h>

#include "solvers/foam_erosion_fem/case/foam_file.hpp"

namespace suite::foam_erosion {

namespace {

struct Column {
  int cells;
  double expansion;
};

// Vertices of station i: 4i bottom-front, 4i+1 top-front, 4i+2 bottom-back, 4i+3 top-back.
std::string hex(int i, const Column& c, int ny, double grading) {
  const int a = 4 * i, b = 4 * (i + 1);
  return fmt::format("    hex ({} {} {} {} {} {} {} {}) ({} {} 1) simpleGrading ({} {} 1)\n", a, b, b + 1, a + 1,
                     a + 2, b + 2, b + 3, a + 3, c.cells, ny, foam_number(c.expansion), foam_number(grading));
}

std::string bottom_face(int i) {
  const int a = 4 * i, b = 4 * (i + 1);
  return fmt::format("            ({} {} {} {})\n", a, a + 2, b + 2, b);
}

}  // namespace

std::string block_mesh_dict(const SectionLayout& L) {
  // Stations: inlet, the dam nodes (upstream toe .. downstream toe), outlet.
  std::vector<Eigen::Vector2d> bottom;
  bottom.emplace_back(L.x_inlet, L.floor);
  bottom.insert(bottom.end(), L.dam_nodes.begin(), L.dam_nodes.end());
  bottom.emplace_back(L.x_outlet, L.floor);
  const int stations = static_cast<int>(bottom.size());
  const int last_block = stations - 2;

  std::string out = foam_header("dictionary", "blockMeshDict", "system");
  out += "scale 1;\n\nvertices\n(\n";
  for (const auto& p : bottom) {
    const std::string x = foam_number(p.x()), yb = foam_number(p.y()), yt = foam_number(L.top),
                      z = foam_number(L.thickness);
    out += fmt::format("    ({} {} 0) ({} {} 0) ({} {} {}) ({} {} {})\n", x, yb, x, yt, x, yb, z, x, yt, z);
  }
  out += ");\n\nblocks\n(\n";
  for (int i = 0; i < stations - 1; ++i) {
    Column c{1, 1.0};
    if (i == 0) c = {L.upstream.cells, L.upstream.expansion};
    if (i == last_block) c = {L.downstream.cells, L.downstream.expansion};
    out += hex(i, c, L.vertical_cells, L.vertical_grading);
  }
  out += ");\n\nedges\n(\n);\n\nboundary\n(\n";
  out += fmt::format("    inlet\n    {{\n        type patch;\n        faces ((0 1 3 2));\n    }}\n");
  const int o = 4 * (stations - 1);
  out += fmt::format("    outlet\n    {{\n        type patch;\n        faces (({} {} {} {}));\n    }}\n", o, o + 2,
                     o + 3, o + 1);
  out += "    atmosphere\n    {\n        type patch;\n        faces\n        (\n";
  for (int i = 0; i < stations - 1; ++i) {
    const int a = 4 * i, b = 4 * (i + 1);
    out += fmt::format("            ({} {} {} {})\n", a + 1, b + 1, b + 3, a + 3);
  }
  out += "        );\n    }\n";
  out += "    floor\n    {\n        type wall;\n        faces\n        (\n";
  out += bottom_face(0) + bottom_face(last_block);
  out += "        );\n    }\n";
  out += "    dam\n    {\n        type wall;\n        faces\n        (\n";
  for (int i = 1; i < last_block; ++i) out += bottom_face(i);
  out += "        );\n    }\n";
  out += "    frontAndBack\n    {\n        type empty;\n        faces\n        (\n";
  for (int i = 0; i < stations - 1; ++i) {
    const int a = 4 * i, b = 4 * (i + 1);
    out += fmt::format("            ({} {} {} {})\n", a, a + 1, b + 1, b);
    out += fmt::format("            ({} {} {} {})\n", a + 2, b + 2, b + 3, a + 3);
  }
  out += "        );\n    }\n);\n\nmergePatchPairs\n(\n);\n";
  return out;
}

}  // namespace suite::foam_erosion
