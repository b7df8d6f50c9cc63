#include "solvers/breach/run/dakota_driver.hpp"

#include "core/dakota/analysis_driver.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/breach/run/run_breach.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace suite::breach {

int run_dakota_driver(const std::optional<std::filesystem::path>& scene_file, const std::string& embedded_text,
                      const std::vector<std::string>& overrides, const std::filesystem::path& parameters,
                      const std::filesystem::path& results) {
  return dakota::run_analysis_driver(mpi::Comm(MPI_COMM_SELF), "breach", overrides, parameters, results,
                                     [&](const std::vector<std::string>& all) {
                                       auto cfg = scene_file ? config::Config::from_file(*scene_file, all)
                                                             : config::Config::from_string(
                                                                   embedded_text, "<embedded embankment_overtopping.yaml>", all);
                                       return make_summary(simulate(Scene::read_complete(cfg))).json();
                                     });
}

}  // namespace suite::breach
