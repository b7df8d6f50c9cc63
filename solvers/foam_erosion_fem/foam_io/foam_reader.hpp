#pragma once
// Reading the ASCII files OpenFOAM writes (writeFormat ascii), as much as the coupling needs:
// polyMesh points, faces, owner and boundary, and the internal and patch values of a field.
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
  std::vector<PatchInfo> patches;

  // Reads constant/polyMesh; `points_file` overrides the points (a moved mesh writes its
  // points into the time directory: <time>/polyMesh/points).
  static PolyMesh read(const std::filesystem::path& poly_mesh_dir, const std::filesystem::path& points_file = {});
  const PatchInfo& patch(const std::string& name) const;  // FoamReadError if absent
  // The patch's points in OpenFOAM's order (primitivePatch::meshPoints: first appearance while
  // walking the patch's faces in order): the order of a point field's patch values.
  std::vector<int> patch_mesh_points(const std::string& name) const;
  int cells() const;
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

// Replaces the body of boundaryField.<patch> in a field file with `entry` (the text between the
// braces), keeping every other byte of the file. FoamReadError if the patch is not there.
void replace_patch_entry(const std::filesystem::path& field_file, const std::string& patch, const std::string& entry);

// The time directories of a case (numeric names), sorted by value; and the latest one.
std::vector<std::filesystem::path> time_directories(const std::filesystem::path& case_dir);
std::filesystem::path latest_time_directory(const std::filesystem::path& case_dir);

}  // namespace suite::foam_erosion
