#pragma once
// The coupled loop's records, rewritten after every coupling step (atomically, so a run that
// stops keeps every step done so far):
//   erosion.csv   one row per erosion step: step, time, eroded area of the step and in total
//                 (m^2 per metre of crest), eroded volume (m^3 over the crest length), the rate
//                 integral it should match, deepest node move, largest element shear, substeps,
//                 nodes clamped at the foundation, whether the flow was re-meshed, flow cells
//   profiles.csv  the dam surface nodes at step 0 (the initial dam) and after every step
#include <filesystem>
#include <string>

#include "solvers/foam_erosion_fem/erosion/fem_erosion.hpp"
#include "solvers/foam_erosion_fem/erosion/surface_curve.hpp"

namespace suite::foam_erosion {

struct ErosionRow {
  int step = 0;
  double time = 0.0;  // flow time at the end of the step, s
  ErosionStepReport report;
  double total_area = 0.0;   // m^2 per metre, since t = 0
  double crest_length = 1.0; // m, for volumes
  double max_shear = 0.0;    // Pa, largest element shear of the step
  bool remeshed = false;
  long long cells = 0;
};

class ErosionRecords {
 public:
  explicit ErosionRecords(std::filesystem::path out_dir);
  // Continues the records in out_dir, dropping rows of steps after `last_step` (a restart).
  ErosionRecords(std::filesystem::path out_dir, int last_step);
  void add_profile(int step, double time, const SurfaceCurve& curve);
  void add_step(const ErosionRow& row);

 private:
  std::filesystem::path dir_;
  std::string erosion_, profiles_;
};

}  // namespace suite::foam_erosion
