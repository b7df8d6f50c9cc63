#include "solvers/foam_erosion_fem/coupling/erosion_records.hpp"

#include <fmt/format.h>

#include <fstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::foam_erosion {

ErosionRecords::ErosionRecords(std::filesystem::path out_dir)
    : dir_(std::move(out_dir)),
      erosion_("step,time_s,eroded_area_m2_per_m,total_eroded_area_m2_per_m,total_eroded_volume_m3,"
               "rate_integral_m2_per_m,max_depth_m,max_shear_Pa,substeps,nodes_clamped,remeshed,cells\n"),
      profiles_("step,time_s,node,x_m,y_m\n") {}

namespace {

// The header and the rows whose first field (the step) is at most last_step.
std::string rows_up_to(const std::filesystem::path& file, int last_step) {
  std::ifstream in(file);
  std::string line, out;
  if (!std::getline(in, line)) throw InputError(fmt::format("{}: missing or empty; cannot restart", file.string()));
  out = line + "\n";
  while (std::getline(in, line))
    if (!line.empty() && std::stoi(line.substr(0, line.find(','))) <= last_step) out += line + "\n";
  return out;
}

}  // namespace

ErosionRecords::ErosionRecords(std::filesystem::path out_dir, int last_step) : dir_(std::move(out_dir)) {
  erosion_ = rows_up_to(dir_ / "erosion.csv", last_step);
  profiles_ = rows_up_to(dir_ / "profiles.csv", last_step);
}

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
