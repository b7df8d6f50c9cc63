#include "solvers/breach/io/dakota_driver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/dakota/parameters_file.hpp"
#include "core/dakota/results_file.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "solvers/breach/io/run_breach.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace suite::breach {

int run_dakota_driver(const std::optional<std::filesystem::path>& scene_file, const std::string& embedded_text,
                      const std::vector<std::string>& overrides, const std::filesystem::path& parameters,
                      const std::filesystem::path& results) {
  std::ifstream in(parameters);
  if (!in) throw InputError(fmt::format("cannot read the Dakota parameters file '{}'", parameters.string()));
  std::stringstream text;
  text << in.rdbuf();
  const auto p = dakota::read_parameters(text.str(), parameters.string());
  std::vector<std::string> all = overrides;
  for (const auto& [name, value] : p.variables) all.push_back(fmt::format("{}={:.17g}", name, value));
  std::string failure;
  std::vector<std::pair<std::string, double>> values;
  try {
    auto cfg = scene_file ? config::Config::from_file(*scene_file, all)
                          : config::Config::from_string(embedded_text, "<embedded embankment_overtopping.yaml>", all);
    const Scene scene = Scene::read_complete(cfg);
    const auto summary = make_summary(simulate(scene)).json();
    for (const auto& r : p.responses) {
      if (!summary.contains(r) || r == "units")
        throw InputError(fmt::format("{}: response '{}' is not a key of the breach summary (docs/breach.md)",
                                     parameters.string(), r));
      const auto& v = summary.at(r);
      if (!(v.is_number() || v.is_boolean())) {
        failure = fmt::format("response '{}' has no value in this run", r);
        break;
      }
      values.emplace_back(r, v.is_boolean() ? (v.get<bool>() ? 1.0 : 0.0) : v.get<double>());
    }
  } catch (const InputError& e) {
    // Values Dakota chose that the scene rejects fail this evaluation, not the study; a key that
    // is not in the scene at all is the user's to fix.
    const std::string what = e.what();
    if (what.find("unknown key") != std::string::npos || what.find("is not a key") != std::string::npos) throw;
    failure = what;
  }
  if (!failure.empty()) {
    std::fprintf(stderr, "breach: evaluation %s failed: %s\n", p.eval_id.c_str(), failure.c_str());
    io::write_file_atomic(results, dakota::write_failure());
    return 0;
  }
  io::write_file_atomic(results, dakota::write_results(values));
  return 0;
}

}  // namespace suite::breach
