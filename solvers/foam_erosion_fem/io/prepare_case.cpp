#include "solvers/foam_erosion_fem/io/prepare_case.hpp"

#include <fmt/format.h>

#include <fstream>
#include <string>

#include "solvers/foam_erosion_fem/case/case_writer.hpp"

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

PreparedCase prepare_case(const FoamScene& scene, FoamRunner& runner, double first_end_time) {
  PreparedCase out;
  out.layout = SectionLayout::initial(scene);
  write_case(scene, out.layout, runner.case_dir(), first_end_time);
  out.runs.push_back(runner.run("blockMesh"));
  out.runs.push_back(runner.run("checkMesh", {"-constant"}));
  require_mesh_ok(out.runs.back(), runner.case_dir());
  out.runs.push_back(runner.run("topoSet", {"-constant"}));
  out.runs.push_back(runner.run("setFields"));
  if (scene.run.ranks > 1) out.runs.push_back(runner.run("decomposePar", {"-force"}));
  return out;
}

}  // namespace suite::foam_erosion
