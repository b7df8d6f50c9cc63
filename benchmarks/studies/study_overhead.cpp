// What a study costs per evaluation beyond the model itself (issue 6's benchmark), one thread:
//   in-process formula      the engine's own cost: design, ledger line, bookkeeping
//   in-process breach model the breach model through the engine (the model is ~1 ms)
//   local process           a trivial external driver (/bin/sh writing a Dakota results file):
//                           work directory, parameters file, fork/exec, results parsing
//   study_overhead [--out FILE.csv] [--repeats R]
// Medians of R repeats, all in one process so their ratios hold on a noisy machine.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/build_info.hpp"
#include "studies/run/study.hpp"

namespace {

namespace fs = std::filesystem;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Seconds per evaluation of a study of `points` evaluations, median over `repeats`.
double per_evaluation(const suite::mpi::Comm& comm, const std::string& spec, int points, int repeats) {
  suite::Logger log(comm, "study", {suite::LogLevel::error, false, nullptr});
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const fs::path dir = fs::temp_directory_path() / ("suite-study-overhead-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "driver.sh") << "#!/bin/sh\necho \"1.0 y\" > \"$2\"\n";
    fs::permissions(dir / "driver.sh", fs::perms::owner_all);
    std::ofstream(dir / "study.yaml") << spec;
    auto cfg = suite::config::Config::from_file(dir / "study.yaml");
    const auto t0 = std::chrono::steady_clock::now();
    suite::studies::run_study(cfg, {dir / "out", false, false, false}, log);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / points);
    fs::remove_all(dir);
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm self(MPI_COMM_SELF);
  std::string out_csv;
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--out") out_csv = argv[i + 1];
    if (a == "--repeats") repeats = std::stoi(argv[i + 1]);
  }
  const std::string common = "execution: {concurrency: 1}\noutput: {plot: false}\n";
  const std::string formula =
      "variables:\n  - {name: x, lower: 0, upper: 1}\n"
      "method: {type: multidim, partitions: 1999}\n"
      "model: {type: expression, responses: {y: \"2*x\"}}\n" +
      common;
  const std::string breach = std::string(
                                 "variables:\n  - {name: kd, lower: 10, upper: 60}\n"
                                 "method: {type: multidim, partitions: 199}\n"
                                 "model:\n  type: breach\n  scene: ") +
                             SUITE_BREACH_DEFAULT_SCENE +
                             "\n  set: {soil.erodibility: \"{kd} cm^3/(N s)\"}\n  responses: [peak_outflow]\n" + common;
  const std::string process =
      "variables:\n  - {name: x, lower: 0, upper: 1}\n"
      "method: {type: multidim, partitions: 199}\n"
      "model:\n  type: command\n  command: [./driver.sh, params.in, results.out]\n"
      "  parameters_file: {name: params.in}\n  results: {file: results.out}\n"
      "  responses: [y]\n  work_directory: {keep: false}\n" +
      common;
  struct Row {
    const char* backend;
    double seconds;
  };
  const std::vector<Row> rows = {{"in-process formula", per_evaluation(self, formula, 2000, repeats)},
                                 {"in-process breach model", per_evaluation(self, breach, 200, repeats)},
                                 {"local process (sh driver)", per_evaluation(self, process, 200, repeats)}};
  for (const auto& r : rows) std::printf("%-28s %10.3f ms per evaluation\n", r.backend, r.seconds * 1e3);
  if (!out_csv.empty()) {
    const auto b = suite::build_info();
    char host[256] = {0};
    gethostname(host, sizeof host - 1);
    std::ofstream csv(out_csv);
    csv << "# study_overhead: host " << host << ", " << sysconf(_SC_NPROCESSORS_ONLN) << " cores, suite " << b.version
        << " (" << b.git_hash << "), " << b.build_type << ", medians of " << repeats
        << " repeats, one evaluation at a time\n";
    csv << "backend,seconds_per_evaluation\n";
    for (const auto& r : rows) csv << r.backend << ',' << r.seconds << '\n';
  }
  return 0;
}
