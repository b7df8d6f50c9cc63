#include "solvers/foam_erosion_fem/case/block_mesh_dict.hpp"

#include <fmt/format.h>

#include <array>

#include "solvers/foam_erosion_fem/case/foam_file.hpp"

namespace suite::foam_erosion {

namespace {

// Vertices of station i: 4i bottom-front, 4i+1 top-front, 4i+2 bottom-back, 4i+3 top-back.
std::string faces_of(int blocks, int (*corner)(int, int), int per_block) {
  std::string out;
  for (int i = 0; i < blocks; ++i)
    for (int k = 0; k < per_block; ++k) {
      const int q = 4 * i;
      out += fmt::format("            ({} {} {} {})\n", corner(q, 4 * k), corner(q, 4 * k + 1), corner(q, 4 * k + 2),
                         corner(q, 4 * k + 3));
    }
  return out;
}

std::string patch(const std::string& name, const std::string& type, const std::string& faces) {
  return fmt::format("    {}\n    {{\n        type {};\n        faces\n        (\n{}        );\n    }}\n", name, type,
                     faces);
}

}  // namespace

std::string block_mesh_dict(const SectionLayout& L) {
  const int blocks = static_cast<int>(L.x_blocks.size());
  std::string out = foam_header("dictionary", "blockMeshDict", "system");
  out += "scale 1;\n\nvertices\n(\n";
  const std::string yb = foam_number(L.floor), yt = foam_number(L.top), z = foam_number(L.thickness);
  for (int i = 0; i <= blocks; ++i) {
    const std::string x = foam_number(i < blocks ? L.x_blocks[static_cast<std::size_t>(i)].x0 : L.x_outlet);
    out += fmt::format("    ({} {} 0) ({} {} 0) ({} {} {}) ({} {} {})\n", x, yb, x, yt, x, yb, z, x, yt, z);
  }
  out += ");\n\nblocks\n(\n";
  for (int i = 0; i < blocks; ++i) {
    const auto& b = L.x_blocks[static_cast<std::size_t>(i)];
    const int a = 4 * i, c = 4 * (i + 1);
    out += fmt::format("    hex ({} {} {} {} {} {} {} {}) ({} {} 1) simpleGrading ({} {} 1)\n", a, c, c + 1, a + 1,
                       a + 2, c + 2, c + 3, a + 3, b.cells, L.vertical_cells, foam_number(b.expansion),
                       foam_number(L.vertical_grading));
  }
  out += ");\n\nedges\n(\n);\n\nboundary\n(\n";
  const int o = 4 * blocks;
  out += patch("inlet", "patch", "            (0 1 3 2)\n");
  out += patch("outlet", "patch", fmt::format("            ({} {} {} {})\n", o, o + 2, o + 3, o + 1));
  // Per block: top (a+1 c+1 c+3 a+3), bottom (a a+2 c+2 c), front (a a+1 c+1 c), back (a+2 c+2 c+3 a+3).
  out += patch("atmosphere", "patch", faces_of(blocks, [](int q, int k) { return q + std::array{1, 5, 7, 3}[k]; }, 1));
  out += patch("floor", "wall", faces_of(blocks, [](int q, int k) { return q + std::array{0, 2, 6, 4}[k]; }, 1));
  out += patch("dam", "wall", "");
  out += patch("frontAndBack", "empty",
               faces_of(blocks, [](int q, int k) { return q + std::array{0, 1, 5, 4, 2, 6, 7, 3}[k]; }, 2));
  out += ");\n\nmergePatchPairs\n(\n);\n";
  return out;
}

}  // namespace suite::foam_erosion
