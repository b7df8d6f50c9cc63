#include "solvers/mpm2grid/io/particle_output.hpp"

#include <vector>

#include "core/io/h5_file.hpp"

namespace suite::mpm2grid {
namespace {

template <int Dim>
std::vector<double> as_xyz(const std::vector<Vec<Dim>>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const auto& x : v) out.insert(out.end(), {x[0], x[1], Dim == 3 ? x[Dim - 1] : 0.0});
  return out;
}

}  // namespace

template <int Dim>
void write_particles(const mpi::Comm& comm, const Simulation<Dim>& sim, const std::filesystem::path& out,
                     const std::string& file_name, io::XdmfSeries* series) {
  io::H5File f(comm, out / file_name, io::H5File::Mode::create);
  std::vector<io::XdmfGrid> grids;
  auto species = [&](const char* name, const Particles<Dim>& P, bool water) {
    const std::string g = std::string("/") + name;
    const auto rows = f.write_rows<double>(g + "/position", as_xyz<Dim>(P.x), 3);
    f.write_rows<double>(g + "/velocity", as_xyz<Dim>(P.v), 3);
    std::vector<double> scalar(P.size());
    for (std::size_t p = 0; p < P.size(); ++p)
      scalar[p] = water ? sim.settings().water.eos.pressure(P.J[p]) : P.saturation[p];
    const std::string scalar_name = water ? "pressure" : "saturation";
    f.write_rows<double>(g + "/" + scalar_name, scalar);
    const std::vector<long long> id(P.id.begin(), P.id.end());
    f.write_rows<long long>(g + "/id", id);
    if (rows.total > 0)
      grids.push_back({name,
                       file_name,
                       io::XdmfTopology::polyvertex,
                       {"position", g + "/position", rows.total, 3},
                       {},
                       {{"velocity", g + "/velocity", rows.total, 3},
                        {scalar_name, g + "/" + scalar_name, rows.total, 1},
                        {"id", g + "/id", rows.total, 1, "Int", 8}},
                       {}});
  };
  species("water", sim.water(), true);
  species("soil", sim.soil(), false);
  f.set_attribute("/", "time", sim.time());
  f.set_attribute("/", "step", sim.steps());
  f.close();
  if (series) series->add_step(sim.time(), grids);
}

template void write_particles<2>(const mpi::Comm&, const Simulation<2>&, const std::filesystem::path&,
                                 const std::string&, io::XdmfSeries*);
template void write_particles<3>(const mpi::Comm&, const Simulation<3>&, const std::filesystem::path&,
                                 const std::string&, io::XdmfSeries*);

}  // namespace suite::mpm2grid
