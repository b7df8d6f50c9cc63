#pragma once
// Lookup tables of marching cubes (Lorensen & Cline, as tabulated by Paul Bourke), in Bourke's
// numbering of a cube's corners and edges.
//
// Corner c sits at grid offset kCornerOffset[c] (x, y, z) from the cube's lowest sample:
//   0 (0,0,0)  1 (1,0,0)  2 (1,1,0)  3 (0,1,0)  4 (0,0,1)  5 (1,0,1)  6 (1,1,1)  7 (0,1,1)
// Edge e joins corners kEdgeCorners[e][0] and kEdgeCorners[e][1].
// The case number of a cube has bit c set when corner c is OUTSIDE (value <= iso).
#include <array>
#include <cstdint>

namespace suite::carving::mc_tables {

inline constexpr std::array<std::array<int, 3>, 8> kCornerOffset = {{
    {0, 0, 0},
    {1, 0, 0},
    {1, 1, 0},
    {0, 1, 0},
    {0, 0, 1},
    {1, 0, 1},
    {1, 1, 1},
    {0, 1, 1},
}};

inline constexpr std::array<std::array<int, 2>, 12> kEdgeCorners = {{
    {0, 1},
    {1, 2},
    {2, 3},
    {3, 0},
    {4, 5},
    {5, 6},
    {6, 7},
    {7, 4},
    {0, 4},
    {1, 5},
    {2, 6},
    {3, 7},
}};

// Bit e set: edge e is crossed by the surface in that case.
extern const std::array<std::uint16_t, 256> kEdgeTable;
// Triangles of each case as edge numbers, three per triangle, counter-clockwise seen from outside,
// ended by -1 (at most five triangles).
extern const std::array<std::array<std::int8_t, 16>, 256> kTriangleTable;

}  // namespace suite::carving::mc_tables
