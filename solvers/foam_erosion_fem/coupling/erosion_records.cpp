#include "solvers/foam_erosion_fem/coupling/erosion_records.hpp"

#include <fmt/format.h>

#include "core/io/atomic_file.hpp"

namespace suite::foam_erosion {

ErosionRecords::ErosionRecords(std::filesystem::path out_dir)
    : dir_(std::move(out_dir)),
      erosion_("step,time_s,eroded_area_m2_per_m,total_eroded_area_m2_per_m,total_eroded_volume_m3,"
               "rate_integral_m2_per_m,max_depth_m,max_shear_Pa,substeps,nodes_clamped,remeshed,cells\n"),
      profiles_("step,time_s,node,x_m,y_m\n") {}

void ErosionRecords::add_profile(int step, double time, const SurfaceCurve& curve) {
  for (int i = 0; i < curve.node_count(); ++i)
    profiles_ += fmt::format("{},{:.9g},{},{:.12g},{:.12g}\n", step, time, i, curve.node(i).x(), curve.node(i).y());
  io::write_file_atomic(dir_ / "profiles.csv", profiles_);
}

void ErosionRecords::add_step(const ErosionRow& r) {
  erosion_ += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{},{},{}\n", r.step, r.time,
                          r.report.eroded_area, r.total_area, r.total_area * r.crest_length, r.report.rate_integral,
                          r.report.max_depth, r.max_shear, r.report.substeps, r.report.nodes_clamped,
                          r.remeshed ? 1 : 0, r.cells);
  io::write_file_atomic(dir_ / "erosion.csv", erosion_);
}

}  // namespace suite::foam_erosion
