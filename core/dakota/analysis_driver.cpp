#include "core/dakota/analysis_driver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/dakota/parameters_file.hpp"
#include "core/dakota/results_file.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::dakota {

namespace {

// An InputError about a key the scene does not have is the user's; any other (a value out of
// range, a check between keys) is about the values Dakota chose, so the evaluation fails.
bool names_an_unknown_key(const std::string& what) {
  return what.find("unknown key") != std::string::npos || what.find("is not a key") != std::string::npos;
}

}  // namespace

nlohmann::json read_summary(const std::filesystem::path& out) {
  const auto path = out / "summary.json";
  std::ifstream in(path);
  if (!in) throw EvaluationFailed(fmt::format("the run wrote no {}", path.string()));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw EvaluationFailed(fmt::format("{} is not JSON: {}", path.string(), e.what()));
  }
}

int run_analysis_driver(const mpi::Comm& comm, const std::string& program, const std::vector<std::string>& overrides,
                        const std::filesystem::path& parameters, const std::filesystem::path& results,
                        const Evaluate& evaluate) {
  std::ifstream in(parameters);
  if (!in) throw InputError(fmt::format("cannot read the Dakota parameters file '{}'", parameters.string()));
  std::stringstream text;
  text << in.rdbuf();
  const auto p = read_parameters(text.str(), parameters.string());
  // The active set vector: per response, 1 asks for its value, 2 its gradient, 4 its Hessian; the
  // results file holds exactly what it asks for. The suite's models return values only, so a
  // derivative or metadata request is the study's to change, before anything runs.
  for (std::size_t i = 0; i < p.asv.size(); ++i)
    if (p.asv[i] & 6)
      throw InputError(fmt::format(
          "{}: response '{}' asks for its {} (ASV {}); {} returns function values only: give Dakota's responses "
          "block numerical_gradients{}",
          parameters.string(), p.responses[i], p.asv[i] & 2 ? "gradient" : "Hessian", p.asv[i], program,
          p.asv[i] & 4 ? " and no_hessians (or numerical_hessians)" : ""));
  if (!p.metadata.empty())
    throw InputError(
        fmt::format("{}: the study asks for metadata ({}); {} returns none: drop the metadata from "
                    "Dakota's responses block",
                    parameters.string(), fmt::join(p.metadata, ", "), program));
  const auto wanted = [&](std::size_t i) { return p.asv.empty() || (p.asv[i] & 1); };
  std::vector<std::string> all = overrides;
  for (const auto& [name, value] : p.variables) all.push_back(fmt::format("{}={:.17g}", name, value));

  std::string failure;
  std::vector<std::pair<std::string, double>> values;
  try {
    const auto summary = evaluate(all);
    for (std::size_t i = 0; i < p.responses.size(); ++i) {
      const std::string& r = p.responses[i];
      if (!summary.contains(r) || r == "units")
        throw InputError(fmt::format("{}: response '{}' is not a key of {}'s summary.json (see its docs)",
                                     parameters.string(), r, program));
      if (!wanted(i)) continue;  // ASV 0: this evaluation does not ask for it
      const auto& v = summary.at(r);
      if (!(v.is_number() || v.is_boolean())) {
        failure = fmt::format("response '{}' has no value in this run", r);
        break;
      }
      values.emplace_back(r, v.is_boolean() ? (v.get<bool>() ? 1.0 : 0.0) : v.get<double>());
    }
  } catch (const InputError& e) {
    if (names_an_unknown_key(e.what())) throw;
    failure = e.what();
  } catch (const EvaluationFailed& e) {
    failure = e.what();
  }
  if (comm.is_root()) {
    if (!failure.empty()) {
      std::fprintf(stderr, "%s: evaluation %s failed: %s\n", program.c_str(), p.eval_id.c_str(), failure.c_str());
      io::write_file_atomic(results, write_failure());
    } else {
      io::write_file_atomic(results, write_results(values));
    }
  }
  return 0;
}

}  // namespace suite::dakota
