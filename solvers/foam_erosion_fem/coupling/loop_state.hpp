#pragma once
// The coupled loop's restart state, state.json in the output folder, rewritten atomically after
// every coupling step: the step and flow time reached, the eroded curve (full precision), the
// curve the current case's mesh was cut along, and the totals. With the case's time directory
// of that time it is everything the loop needs to go on; since the loop restarts interFoam from
// its written fields at every step anyway, a resumed run repeats the uninterrupted one exactly.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace suite::foam_erosion {

struct LoopState {
  int step = 0;
  double time = 0.0;
  int remeshes = 0;
  double eroded_area = 0.0;
  std::vector<Eigen::Vector2d> nodes;       // the FEM curve after `step`
  std::vector<Eigen::Vector2d> mesh_nodes;  // the curve the case's mesh is cut along

  void write(const std::filesystem::path& file) const;
  // InputError naming the file if it is missing or malformed.
  static LoopState read(const std::filesystem::path& file);
};

}  // namespace suite::foam_erosion
