#pragma once
// Reading the ASCII files OpenFOAM writes (writeFormat ascii), as much as the coupling needs:
// polyMesh points, faces, owner, neighbour and boundary, and the internal and patch values of a field.
// Lists come as "N ( ... )", "N{value}" (all equal) or "uniform v"; "//" and "/* */" comments
// and the FoamFile header are skipped. Every error names the file and what was expected.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace suite::foam_erosion {

struct PatchInfo {
  std::string name, type;
  int start_face = 0, faces = 0;
};

struct PolyMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  std::vector<int> owner;
  std::vector<int> neighbour;  // one per internal face (the faces before the first patch)
  std::vector<PatchInfo> patches;

  // Reads a polyMesh directory (constant/polyMesh).
  static PolyMesh read(const std::filesystem::path& poly_mesh_dir);
  const PatchInfo& patch(const std::string& name) const;  // FoamReadError if absent
  int cells() const;
  // The mean of each cell's points: the centroid for the axis-aligned boxes this solver meshes.
  std::vector<Eigen::Vector3d> cell_centres() const;
  // Cell volumes by the divergence theorem, V = sum over faces of (x_f . S_f) / 3, outward S_f.
  std::vector<double> cell_volumes() const;
  // Centre (mean of the points) and area vector (outward from the owner) of a face.
  Eigen::Vector3d face_centre(int face) const;
  Eigen::Vector3d face_area(int face) const;
};

class FoamReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A field's values: the internal field (cells) and one patch's value entry; a uniform entry is
// expanded to `size` values. Components: 1 (scalar) or 3 (vector), row per value.
struct FieldValues {
  std::vector<double> values;  // size * components
  int components = 1;
  std::size_t size() const { return values.size() / components; }
  double at(std::size_t i, int c = 0) const { return values[i * components + c]; }
};
FieldValues read_internal_field(const std::filesystem::path& field_file, int components, std::size_t size);
FieldValues read_patch_value(const std::filesystem::path& field_file, const std::string& patch, int components,
                             std::size_t size);


// Replaces the internalField entry of a scalar field file with `values` (nonuniform list, %.12g),
// keeping every other byte. FoamReadError names the file if it has no internalField.
void write_internal_scalar_field(const std::filesystem::path& field_file, const std::vector<double>& values);

// The time directories of a case (numeric names), sorted by value; and the latest one.
std::vector<std::filesystem::path> time_directories(const std::filesystem::path& case_dir);
std::filesystem::path latest_time_directory(const std::filesystem::path& case_dir);

}  // namespace suite::foam_erosion
