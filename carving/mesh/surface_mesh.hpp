#pragma once
// A triangle mesh of a seed's surface (docs/methods/carving.md): its area, the volume it encloses, a check
// that it is closed, and binary PLY output.
//
// Units: vertex coordinates in mm, so areas are in mm^2 and volumes in mm^3. Triangles hold indices
// into `vertices` and are counter-clockwise seen from outside, so their normals point outward.
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <vector>

namespace suite::carving {

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> vertices;      // mm
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside (outward normals)
};

// Sum of the triangles' areas, mm^2.
double surface_area(const SurfaceMesh& mesh);

// Volume enclosed by a closed mesh, mm^3, by the divergence theorem (sum of the signed volumes of the
// tetrahedra that join each triangle to a reference point). Positive when the triangles are oriented
// outward. For an open mesh the number depends on the reference point (the centre of the vertices'
// bounding box) and has no meaning.
double enclosed_volume(const SurfaceMesh& mesh);

// True when every edge is shared by exactly two triangles that run along it in opposite directions
// (closed, consistently oriented, manifold edges). An empty mesh is closed; a triangle with a repeated
// or out-of-range index makes the mesh not closed.
bool is_closed(const SurfaceMesh& mesh);

// Writes a binary little-endian PLY file ("format binary_little_endian 1.0"; vertex: float x y z;
// face: list uchar int vertex_indices). The data go to a temporary file in the same folder which is
// then renamed onto `file`, so readers never see a half-written mesh. Throws suite::InputError naming
// `file` if it cannot be written, std::invalid_argument if a triangle's index is out of range.
void write_ply(const std::filesystem::path& file, const SurfaceMesh& mesh);

// Reads a PLY file of the format write_ply writes (comment and obj_info lines are allowed). Throws
// suite::InputError naming `file` if it cannot be read or is not in that format.
SurfaceMesh read_ply(const std::filesystem::path& file);

}  // namespace suite::carving
