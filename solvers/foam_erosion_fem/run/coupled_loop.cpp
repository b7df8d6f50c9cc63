#include "solvers/foam_erosion_fem/run/coupled_loop.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/errors.hpp"
#include "solvers/foam_erosion_fem/case/case_writer.hpp"
#include "solvers/foam_erosion_fem/case/dam_cells.hpp"
#include "solvers/foam_erosion_fem/coupling/erosion_records.hpp"
#include "solvers/foam_erosion_fem/coupling/remesh.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"
#include "solvers/foam_erosion_fem/coupling/wall_shear.hpp"
#include "solvers/foam_erosion_fem/erosion/fem_erosion.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

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

PreparedCase resume_case(const FoamScene& s, const fs::path& case_dir, const LoopState& state) {
  // Time directories past the state's time belong to the segment that was interrupted, and so
  // do the discharge records that started at its time.
  // (Also in processor*/ of a decomposed case.)
  std::vector<fs::path> roots{case_dir};
  for (const auto& d : fs::directory_iterator(case_dir))
    if (d.is_directory() && d.path().filename().string().rfind("processor", 0) == 0) roots.push_back(d.path());
  for (const auto& root : roots)
    for (const auto& t : time_directories(root))
      if (std::stod(t.filename().string()) > state.time * (1 + 1e-12) + 1e-12) fs::remove_all(t);
  if (fs::is_directory(case_dir / "postProcessing"))
    for (const auto& fo : fs::directory_iterator(case_dir / "postProcessing"))
      for (const auto& start : fs::directory_iterator(fo.path())) {
        char* end = nullptr;
        const std::string name = start.path().filename().string();
        const double t0 = std::strtod(name.c_str(), &end);
        if (end && *end == '\0' && t0 >= state.time * (1 - 1e-12) - 1e-12) fs::remove_all(start.path());
      }
  PreparedCase p;
  p.layout = SectionLayout::initial(s).with_dam_nodes(state.mesh_nodes);
  p.mesh.background_centres = PolyMesh::read(case_dir / "constant/background").cell_centres();
  p.mesh.fluid = fluid_cells(p.mesh.background_centres, p.layout);
  p.mesh.background_cells = p.layout.background_cells();
  const auto mesh = PolyMesh::read(case_dir / "constant/polyMesh");
  p.mesh.cells = mesh.cells();
  p.mesh.dam_faces = mesh.patch(kDamPatch).faces;
  if (p.mesh.cells != static_cast<long long>(p.mesh.fluid.size()))
    throw InputError(fmt::format("{}: the mesh has {} cells but the restart state's curve cuts {}; the case does not "
                                 "belong to this state.json (or the scene's mesh changed): start again without "
                                 "--restart",
                                 case_dir.string(), p.mesh.cells, p.mesh.fluid.size()));
  p.layout = p.layout.with_dam_nodes(state.nodes);
  return p;
}

CoupledRunResult run_coupled(const FoamScene& s, FoamRunner& runner, PreparedCase& prepared, const fs::path& out,
                             Logger& log, PhaseTimers& timers, const LoopState* resume) {
  CoupledRunResult r;
  SurfaceCurve curve(prepared.layout.dam_nodes);
  ErosionRecords records = resume ? ErosionRecords(out, resume->step) : ErosionRecords(out);
  if (!resume) records.add_profile(0, 0.0, curve);
  LoopState state;
  state.nodes = state.mesh_nodes = prepared.layout.dam_nodes;
  if (resume) state = *resume;
  const auto settings = erosion_settings(s);
  const bool erodes = s.soil.kd > 0.0;
  const double interval = s.coupling.interval;
  const int steps = erodes ? std::max(1, static_cast<int>(std::ceil(s.time.end / interval - 1e-9))) : 1;
  const auto end_of = [&](int k) { return erodes ? std::min(k * interval, s.time.end) : s.time.end; };
  SectionLayout layout = prepared.layout;
  double t_prev = state.time;
  r.final_crest = highest_node(curve);
  r.erosion_steps = state.step;
  r.remeshes = state.remeshes;
  r.eroded_area = state.eroded_area;
  const int first = state.step + 1;
  // A state saved after the last step of a shorter run may still need the re-mesh that step
  // skipped (nothing followed it).
  if (resume && first <= steps && fluid_cells(prepared.mesh.background_centres, layout) != prepared.mesh.fluid) {
    ScopedPhase remesh_phase(timers, "remesh");
    prepared.mesh = remesh_case(s, layout, prepared.mesh, runner,
                                out / "cases" / fmt::format("segment_{:03d}", r.remeshes), end_of(first), prepared.runs);
    ++r.remeshes;
    state.mesh_nodes = curve.nodes();
    log.info("re-meshed for the curve of step {} (the run that reached it stopped there): {} flow cells", state.step,
             prepared.mesh.cells);
  }

  for (int k = first; k <= steps; ++k) {
    // A failed OpenFOAM program or an unreadable result ends the loop as a failed step: every
    // finished step stays in the records and the result, and the message says which step failed.
    try {
      write_control_dict(s, runner.case_dir(), end_of(k));
      {
        ScopedPhase phase(timers, "flow");
        const auto flow = runner.run("interFoam", {}, s.run.ranks, "", /*stoppable=*/true);
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
      row.total_area = r.eroded_area + row.report.eroded_area;
      layout = layout.with_dam_nodes(curve.nodes());
      // The re-mesh for the next step first: the result and the records take the step once it
      // is complete.
      if (k < steps && fluid_cells(prepared.mesh.background_centres, layout) != prepared.mesh.fluid) {
        ScopedPhase remesh_phase(timers, "remesh");
        prepared.mesh = remesh_case(s, layout, prepared.mesh, runner,
                                    out / "cases" / fmt::format("segment_{:03d}", r.remeshes), end_of(k + 1), prepared.runs);
        row.remeshed = true;
        ++r.remeshes;
        state.mesh_nodes = curve.nodes();
      }
      t_prev = t_now;
      r.eroded_area = row.total_area;
      r.erosion_steps = k;
      r.final_crest = highest_node(curve);
      row.cells = prepared.mesh.cells;
      records.add_step(row);
      records.add_profile(k, t_now, curve);
      state.step = k;
      state.time = t_now;
      state.remeshes = r.remeshes;
      state.eroded_area = r.eroded_area;
      state.nodes = curve.nodes();
      state.write(out / "state.json");
      log.info("erosion step {} at t = {} s: max shear {:.3g} Pa, eroded {:.3g} m^2/m ({:.3g} in total), deepest {:.3g} m{}",
               k, t_now, row.max_shear, row.report.eroded_area + 0.0, r.eroded_area, row.report.max_depth,
               row.remeshed ? fmt::format(", re-meshed: {} flow cells", prepared.mesh.cells) : "");
    } catch (const FoamRunError& e) {
      r.failure = fmt::format("coupling step {} of {} (flow from t = {} to {} s): {}", k, steps, t_prev, end_of(k), e.what());
      return r;
    } catch (const FoamReadError& e) {
      r.failure = fmt::format("coupling step {} of {} (flow from t = {} to {} s): cannot read its result: {}", k, steps,
                              t_prev, end_of(k), e.what());
      return r;
    }
  }
  prepared.layout = layout;
  return r;
}

}  // namespace suite::foam_erosion
