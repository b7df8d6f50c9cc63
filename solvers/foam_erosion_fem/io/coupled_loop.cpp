#include "solvers/foam_erosion_fem/io/coupled_loop.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solvers/foam_erosion_fem/case/case_writer.hpp"
#include "solvers/foam_erosion_fem/case/dam_cells.hpp"
#include "solvers/foam_erosion_fem/coupling/erosion_records.hpp"
#include "solvers/foam_erosion_fem/coupling/remesh.hpp"
#include "solvers/foam_erosion_fem/coupling/wall_shear.hpp"
#include "solvers/foam_erosion_fem/erosion/fem_erosion.hpp"
#include "solvers/foam_erosion_fem/foam_io/foam_reader.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

ErosionSettings erosion_settings(const FoamScene& s) {
  ErosionSettings e;
  e.law = {s.soil.kd, s.soil.tau_c};
  e.morphological_factor = s.coupling.morphological_factor;
  e.min_element_length = 0.05 * s.mesh.cell_size;
  e.foundation_level = s.dam.foundation;
  e.repose_angle_deg = s.soil.repose_angle;
  return e;
}

double highest_node(const SurfaceCurve& c) {
  double y = -1e300;
  for (const auto& p : c.nodes()) y = std::max(y, p.y());
  return y;
}

}  // namespace

CoupledRunResult run_coupled(const FoamScene& s, FoamRunner& runner, PreparedCase& prepared, const fs::path& out,
                             Logger& log, PhaseTimers& timers) {
  CoupledRunResult r;
  SurfaceCurve curve(prepared.layout.dam_nodes);
  ErosionRecords records(out);
  records.add_profile(0, 0.0, curve);
  const auto settings = erosion_settings(s);
  const bool erodes = s.soil.kd > 0.0;
  const double interval = s.coupling.interval;
  const int steps = erodes ? std::max(1, static_cast<int>(std::ceil(s.time.end / interval - 1e-9))) : 1;
  const auto end_of = [&](int k) { return erodes ? std::min(k * interval, s.time.end) : s.time.end; };
  SectionLayout layout = prepared.layout;
  double t_prev = 0.0;
  r.final_crest = highest_node(curve);

  for (int k = 1; k <= steps; ++k) {
    write_control_dict(s, runner.case_dir(), end_of(k));
    {
      ScopedPhase phase(timers, "flow");
      const auto flow = runner.run("interFoam", {}, s.run.ranks);
      r.flow_steps += flow.time_steps;
      r.max_courant = std::max(r.max_courant, flow.max_courant);
      log.info("flow to t = {} s: {} steps in {:.1f} s, max Courant {:.3g}", end_of(k), flow.time_steps,
               flow.wall_seconds, flow.max_courant);
    }
    if (s.run.ranks > 1) runner.run("reconstructPar", {"-latestTime"});
    if (!erodes) break;

    ScopedPhase phase(timers, "erosion");
    const fs::path latest = latest_time_directory(runner.case_dir());
    const double t_now = std::stod(latest.filename().string());
    const auto faces = read_wall_shear(runner.case_dir(), latest, kDamPatch, s.flow.water, s.flow.air);
    const auto shear = shear_on_elements(curve.nodes(), faces);
    ErosionRow row;
    row.step = k;
    row.time = t_now;
    row.crest_length = s.dam.crest_length;
    row.max_shear = *std::max_element(shear.begin(), shear.end());
    try {
      row.report = erode(curve, shear, t_now - t_prev, settings);
    } catch (const CurveValidityError& e) {
      r.failure = fmt::format("erosion step {} at t = {} s: {}", k, t_now, e.what());
      return r;
    }
    t_prev = t_now;
    r.eroded_area += row.report.eroded_area;
    row.total_area = r.eroded_area;
    r.erosion_steps = k;
    r.final_crest = highest_node(curve);
    layout = layout.with_dam_nodes(curve.nodes());
    if (k < steps && fluid_cells(prepared.mesh.background_centres, layout) != prepared.mesh.fluid) {
      ScopedPhase remesh_phase(timers, "remesh");
      prepared.mesh = remesh_case(s, layout, prepared.mesh, runner,
                                  out / "cases" / fmt::format("segment_{:03d}", r.remeshes), end_of(k + 1), prepared.runs);
      row.remeshed = true;
      ++r.remeshes;
    }
    row.cells = prepared.mesh.cells;
    records.add_step(row);
    records.add_profile(k, t_now, curve);
    log.info("erosion step {} at t = {} s: max shear {:.3g} Pa, eroded {:.3g} m^2/m ({:.3g} in total), deepest {:.3g} m{}",
             k, t_now, row.max_shear, row.report.eroded_area + 0.0, r.eroded_area, row.report.max_depth,
             row.remeshed ? fmt::format(", re-meshed: {} flow cells", prepared.mesh.cells) : "");
  }
  prepared.layout = layout;
  return r;
}

}  // namespace suite::foam_erosion
