// Marching cubes over a regular grid, one slice of cubes at a time, with one shared vertex per crossed
// grid edge.
#include "carving/mesh/marching_cubes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

#include "carving/mesh/marching_cubes_tables.hpp"

namespace suite::carving {

namespace {

using mc_tables::kCornerOffset;
using mc_tables::kEdgeCorners;

// Where the vertex of a cube edge is kept. The grid edges of one layer of cubes (between slices k and
// k + 1) are: x and y edges in slice k ("low") and in slice k + 1 ("high"), and z edges between them.
enum EdgeArray { kXLow, kXHigh, kYLow, kYHigh, kZ, kEdgeArrays };

struct EdgeSlot {
  int axis = 0;                 // 0, 1, 2 for x, y, z
  int start = 0, end = 0;       // corner at the lower end of the edge, and the other one
  std::array<int, 3> offset{};  // grid offset of `start` from the cube's lowest sample
  EdgeArray array = kXLow;
};

constexpr std::array<EdgeSlot, 12> make_edge_slots() {
  std::array<EdgeSlot, 12> slots{};
  for (int e = 0; e < 12; ++e) {
    int a = kEdgeCorners[e][0], b = kEdgeCorners[e][1];
    int axis = 0;
    while (kCornerOffset[a][axis] == kCornerOffset[b][axis]) ++axis;
    if (kCornerOffset[a][axis] > kCornerOffset[b][axis]) std::swap(a, b);
    EdgeSlot& s = slots[e];
    s.axis = axis;
    s.start = a;
    s.end = b;
    s.offset = kCornerOffset[a];
    const bool high = s.offset[2] == 1;
    s.array = axis == 0 ? (high ? kXHigh : kXLow) : axis == 1 ? (high ? kYHigh : kYLow) : kZ;
  }
  return slots;
}

constexpr std::array<EdgeSlot, 12> kEdgeSlots = make_edge_slots();

}  // namespace

SurfaceMesh marching_cubes(const ScalarField& field, float iso) {
  const auto [n0, n1, n2] = field.n;
  if (n0 < 0 || n1 < 0 || n2 < 0) {
    throw std::invalid_argument(fmt::format("marching_cubes: negative sample count {} x {} x {}", n0, n1, n2));
  }
  const auto nx = static_cast<std::size_t>(n0), ny = static_cast<std::size_t>(n1), nz = static_cast<std::size_t>(n2);
  if (field.values.size() != nx * ny * nz) {
    throw std::invalid_argument(
        fmt::format("marching_cubes: {} values for a grid of {} x {} x {} samples", field.values.size(), n0, n1, n2));
  }
  if (!(field.spacing > 0) || !std::isfinite(field.spacing)) {
    throw std::invalid_argument(fmt::format("marching_cubes: spacing {} is not a positive number", field.spacing));
  }
  SurfaceMesh mesh;
  if (nx < 2 || ny < 2 || nz < 2) return mesh;

  // Vertex number of each grid edge of the current layer of cubes, -1 until made. An edge is found by
  // the sample at its lower end: index i + nx * j in its array.
  const std::size_t plane = nx * ny;
  std::array<std::vector<int>, kEdgeArrays> edge_vertex;
  for (auto& ids : edge_vertex) ids.assign(plane, -1);

  const float* values = field.values.data();
  for (std::size_t k = 0; k + 1 < nz; ++k) {
    if (k > 0) {
      // The top slice of the last layer is the bottom slice of this one.
      std::swap(edge_vertex[kXLow], edge_vertex[kXHigh]);
      std::swap(edge_vertex[kYLow], edge_vertex[kYHigh]);
      std::fill(edge_vertex[kXHigh].begin(), edge_vertex[kXHigh].end(), -1);
      std::fill(edge_vertex[kYHigh].begin(), edge_vertex[kYHigh].end(), -1);
      std::fill(edge_vertex[kZ].begin(), edge_vertex[kZ].end(), -1);
    }
    for (std::size_t j = 0; j + 1 < ny; ++j) {
      // The four rows of samples along x that a row of cubes touches: (j, k), (j + 1, k), (j, k + 1),
      // (j + 1, k + 1). Corner c of cube i reads rows[c] at i + kCornerOffset[c][0].
      const float* row_jk = values + nx * (j + ny * k);
      std::array<const float*, 8> rows{};
      for (int c = 0; c < 8; ++c) {
        rows[c] = row_jk + nx * static_cast<std::size_t>(kCornerOffset[c][1]) +
                  plane * static_cast<std::size_t>(kCornerOffset[c][2]);
      }
      // Outside is "not above iso", so a NaN sample counts as outside.
      const auto outside = [&](int corner, std::size_t i) -> unsigned {
        return !(rows[corner][i] > iso) ? 1u << corner : 0u;
      };
      // The corners at x = i of the cube (0, 3, 4, 7) are the corners at x = i + 1 (1, 2, 5, 6) of the
      // cube before it, so each cube reads four new samples.
      unsigned low_x = outside(0, 0) | outside(3, 0) | outside(4, 0) | outside(7, 0);
      for (std::size_t i = 0; i + 1 < nx; ++i) {
        const unsigned cube_case =
            low_x | outside(1, i + 1) | outside(2, i + 1) | outside(5, i + 1) | outside(6, i + 1);
        low_x = ((cube_case >> 1) & 1u) | ((cube_case >> 2) & 1u) << 3 | ((cube_case >> 5) & 1u) << 4 |
                ((cube_case >> 6) & 1u) << 7;
        if (cube_case == 0 || cube_case == 255) continue;

        const unsigned crossed = mc_tables::kEdgeTable[cube_case];
        std::array<int, 12> vertex{};
        for (int e = 0; e < 12; ++e) {
          if ((crossed & (1u << e)) == 0) continue;
          const EdgeSlot& s = kEdgeSlots[e];
          const std::size_t i0 = i + static_cast<std::size_t>(s.offset[0]);
          const std::size_t j0 = j + static_cast<std::size_t>(s.offset[1]);
          int& id = edge_vertex[s.array][i0 + nx * j0];
          if (id < 0) {
            // Linear interpolation between the edge's two samples (in double, so t is exact enough).
            const double v0 = rows[s.start][i + static_cast<std::size_t>(kCornerOffset[s.start][0])];
            const double v1 = rows[s.end][i + static_cast<std::size_t>(kCornerOffset[s.end][0])];
            double t = (iso - v0) / (v1 - v0);
            if (!(t >= 0 && t <= 1)) t = 0.5;  // only with NaN samples
            Eigen::Vector3d p(static_cast<double>(i0), static_cast<double>(j0),
                              static_cast<double>(k + static_cast<std::size_t>(s.offset[2])));
            p[s.axis] += t;
            if (mesh.vertices.size() >= static_cast<std::size_t>(INT_MAX)) {
              throw std::length_error("marching_cubes: the mesh needs more than INT_MAX vertices");
            }
            mesh.vertices.push_back(field.origin + field.spacing * p);
            id = static_cast<int>(mesh.vertices.size() - 1);
          }
          vertex[e] = id;
        }
        const auto& triangles = mc_tables::kTriangleTable[cube_case];
        for (int t = 0; triangles[t] >= 0; t += 3) {
          mesh.triangles.push_back({vertex[triangles[t]], vertex[triangles[t + 1]], vertex[triangles[t + 2]]});
        }
      }
    }
  }
  return mesh;
}

}  // namespace suite::carving
