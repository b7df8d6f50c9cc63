#include "solvers/foam_erosion_fem/coupling/remesh.hpp"

#include <limits>
#include <set>

#include "solvers/foam_erosion_fem/case/case_writer.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

// Water fraction of the opened cells from the nearest cell of the old mesh. Both cases' cells are
// their background cells in increasing order (subsetMesh keeps the order of the set).
void fill_opened_cells(const MeshedSection& old_mesh, const MeshedSection& mesh, const fs::path& old_alpha,
                       const fs::path& new_alpha) {
  const auto& centres = mesh.background_centres;
  std::vector<char> was_fluid(centres.size(), 0);
  for (int c : old_mesh.fluid) was_fluid[static_cast<std::size_t>(c)] = 1;
  const auto before = read_internal_field(old_alpha, 1, old_mesh.fluid.size());
  auto after = read_internal_field(new_alpha, 1, mesh.fluid.size()).values;
  bool changed = false;
  for (std::size_t j = 0; j < mesh.fluid.size(); ++j) {
    const auto cell = static_cast<std::size_t>(mesh.fluid[j]);
    if (was_fluid[cell]) continue;
    std::size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < old_mesh.fluid.size(); ++i) {
      const double d = (centres[static_cast<std::size_t>(old_mesh.fluid[i])] - centres[cell]).squaredNorm();
      if (d < best) best = d, nearest = i;
    }
    after[j] = before.at(nearest);
    changed = true;
  }
  if (changed) write_internal_scalar_field(new_alpha, after);
}

}  // namespace

MeshedSection remesh_case(const FoamScene& scene, const SectionLayout& layout, const MeshedSection& old_mesh,
                          FoamRunner& runner, const fs::path& archive_dir, double end_time,
                          std::vector<ProgramRun>& runs) {
  const fs::path case_dir = runner.case_dir();
  const std::string time_name = latest_time_directory(case_dir).filename().string();
  fs::create_directories(archive_dir.parent_path());
  fs::remove_all(archive_dir);
  fs::rename(case_dir, archive_dir);

  write_case_setup(scene, layout, case_dir, end_time);
  MeshedSection mesh = mesh_section(layout, runner, runs);
  write_initial_fields(scene, layout, case_dir);
  runs.push_back(runner.run("topoSet", {"-constant"}));
  // The fields start where the old case stopped: the new case's only time is that time, and
  // mapFields (startFrom latestTime) writes the mapped fields into it over the initial ones,
  // keeping their boundary conditions.
  fs::rename(case_dir / "0", case_dir / time_name);
  std::set<fs::path> initial;
  for (const auto& f : fs::directory_iterator(case_dir / time_name)) initial.insert(f.path().filename());
  // mapFields maps every field of the source time, and gives the derived ones (p,
  // wallShearStress) whatever was in memory in the cells it cannot map: writing those, OpenFOAM
  // v1912 can trip its floating-point trap (SIGFPE), depending on the memory it was given (seen
  // with one process environment and not another). Only the fields the new case starts from are
  // mapped: the others wait outside the archived case and go back after.
  const fs::path source = archive_dir / time_name, aside = archive_dir.string() + ".derived_fields";
  fs::remove_all(aside);
  fs::create_directories(aside);
  for (const auto& f : fs::directory_iterator(source))
    if (f.is_regular_file() && !initial.count(f.path().filename())) fs::rename(f.path(), aside / f.path().filename());
  runs.push_back(runner.run("mapFields", {archive_dir.string(), "-consistent", "-sourceTime", "latestTime",
                                          "-mapMethod", "mapNearest"}));
  for (const auto& f : fs::directory_iterator(aside)) fs::rename(f.path(), source / f.path().filename());
  fs::remove(aside);
  // Anything mapFields made beyond the initial fields: the solver recomputes it, decomposePar
  // would choke on it.
  for (const auto& f : fs::directory_iterator(case_dir / time_name))
    if (!initial.count(f.path().filename())) fs::remove_all(f.path());
  fill_opened_cells(old_mesh, mesh, archive_dir / time_name / "alpha.water", case_dir / time_name / "alpha.water");
  if (fs::exists(archive_dir / "postProcessing"))
    fs::copy(archive_dir / "postProcessing", case_dir / "postProcessing", fs::copy_options::recursive);
  if (scene.run.ranks > 1) runs.push_back(runner.run("decomposePar", {"-force"}));
  return mesh;
}

}  // namespace suite::foam_erosion
