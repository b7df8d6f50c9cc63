#include "solvers/foam_erosion_fem/run/prepare_case.hpp"

#include <fmt/format.h>

#include <fstream>
#include <string>

#include "solvers/foam_erosion_fem/case/case_writer.hpp"
#include "solvers/foam_erosion_fem/case/dam_cells.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

namespace suite::foam_erosion {

namespace {

// checkMesh ends with "Mesh OK." or "Failed N mesh checks."; its exit status does not tell.
void require_mesh_ok(const ProgramRun& check, const std::filesystem::path& case_dir) {
  std::ifstream in(check.log);
  std::string line, failures;
  bool ok = false;
  while (std::getline(in, line)) {
    if (line.find("Mesh OK.") != std::string::npos) ok = true;
    if (line.find("***") != std::string::npos) failures += "\n    | " + line;
  }
  if (!ok)
    throw FoamRunError(fmt::format("checkMesh rejected the mesh of case {} (log {}):{}", case_dir.string(),
                                   check.log.string(), failures.empty() ? " no \"Mesh OK.\" in its log" : failures));
}

}  // namespace

MeshedSection mesh_section(const SectionLayout& layout, FoamRunner& runner, std::vector<ProgramRun>& runs) {
  const auto poly_mesh = runner.case_dir() / "constant/polyMesh";
  std::filesystem::remove_all(poly_mesh);
  runs.push_back(runner.run("blockMesh"));
  // The background stays in the case (constant/background, which OpenFOAM does not read): a
  // restarted run finds the flow cells of an eroded curve from it.
  const auto background = runner.case_dir() / "constant/background";
  std::filesystem::remove_all(background);
  std::filesystem::copy(poly_mesh, background, std::filesystem::copy_options::recursive);
  MeshedSection out;
  out.background_centres = PolyMesh::read(poly_mesh).cell_centres();
  out.fluid = fluid_cells(out.background_centres, layout);
  out.background_cells = layout.background_cells();
  write_cell_set(runner.case_dir(), kFluidCellSet, out.fluid);
  runs.push_back(runner.run("subsetMesh", {kFluidCellSet, "-patch", kDamPatch, "-overwrite"}));
  runs.push_back(runner.run("checkMesh", {"-constant"}));
  require_mesh_ok(runs.back(), runner.case_dir());
  const auto mesh = PolyMesh::read(poly_mesh);
  out.cells = mesh.cells();
  out.dam_faces = mesh.patch(kDamPatch).faces;
  return out;
}

PreparedCase prepare_case(const FoamScene& scene, FoamRunner& runner, double first_end_time) {
  PreparedCase out;
  out.layout = SectionLayout::initial(scene);
  write_case_setup(scene, out.layout, runner.case_dir(), first_end_time);
  out.mesh = mesh_section(out.layout, runner, out.runs);
  write_initial_fields(scene, out.layout, runner.case_dir());
  out.runs.push_back(runner.run("topoSet", {"-constant"}));
  out.runs.push_back(runner.run("setFields"));
  if (scene.run.ranks > 1) out.runs.push_back(runner.run("decomposePar", {"-force"}));
  return out;
}

}  // namespace suite::foam_erosion
