#pragma once
// A suite executable as a Dakota analysis driver (docs/methods/studies.md):
//
//   <program> [scene.yaml] [key.path=value ...] --dakota params.in results.out
//
// Each variable of the parameters file is named by a scene key and overrides it, after the
// command line's overrides (its value in the key's SI unit, e.g. soil.erodibility in
// m^3/(N s)); `evaluate` runs the model with those overrides and returns its summary.json
// content; each response is named by a key of that summary and written, labelled, to the
// results file. An evaluation fails ("FAIL" in the results file, which Dakota's failure capture
// understands, exit status 0) when the scene rejects the values Dakota chose (a negative kd),
// when `evaluate` throws EvaluationFailed (the run did not finish), or when a response has no
// value in this run. A broken parameters file, a variable that is not a scene key and a
// response that is not a summary key are the user's to fix: InputError. The active set vector is
// honoured: a response with ASV 0 is left out of the results file; a gradient or Hessian request
// (ASV 2, 4) or metadata is an InputError naming the response and Dakota's numerical_gradients,
// since the models return values only.
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/mpi/comm.hpp"

namespace suite::dakota {

// The run of one evaluation did not finish (a solver step failed, the run was stopped).
class EvaluationFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs the model with these overrides (the command line's, then the parameters file's) and
// returns its summary.json content. COLLECTIVE over the driver's communicator.
using Evaluate = std::function<nlohmann::json(const std::vector<std::string>& overrides)>;

// COLLECTIVE over comm: every rank reads the parameters file and calls `evaluate`; rank 0
// writes the results file. Returns the exit status (0, also for a failed evaluation).
int run_analysis_driver(const mpi::Comm& comm, const std::string& program, const std::vector<std::string>& overrides,
                        const std::filesystem::path& parameters, const std::filesystem::path& results,
                        const Evaluate& evaluate);

// The summary.json an executable wrote into `out`, for an `evaluate` that runs the executable's
// usual path; EvaluationFailed if it is missing or unreadable.
nlohmann::json read_summary(const std::filesystem::path& out);

}  // namespace suite::dakota
