// What a study costs per evaluation beyond the model itself (issue 6's benchmark), one thread:
//   in-process formula      the engine's own cost: design, ledger line, bookkeeping
//   in-process breach model the breach model through the engine, its scene read once per study
//                           and each evaluation's kd set on a copy (breach::SceneVariants)
//   ... scene read every evaluation   the same with `read_scene: every_evaluation` (the path
//                           before SceneVariants: the scene file read with kd as an override)
//   breach model alone      simulate + summary of the read scene, no engine: the model's part
//   local process           a trivial external driver (/bin/sh writing a Dakota results file):
//                           work directory, parameters file, fork/exec, results parsing
// and, with --dissertation SPEC, the wall time of that whole study (the dissertation's 216
// breach runs) on 2 threads, without and with its charts, and with the scene read each time.
//   study_overhead [--out FILE.csv] [--repeats R] [--dissertation SPEC --wall-out FILE.csv]
// Medians of R repeats, all in one process so their ratios hold on a noisy machine.
#include <fmt/format.h>
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
#include "solvers/breach/run/run_breach.hpp"
#include "solvers/breach/model/scene.hpp"
#include "solvers/breach/model/simulate.hpp"
#include "studies/run/study.hpp"

namespace {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

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
    const auto t0 = Clock::now();
    suite::studies::run_study(cfg, {dir / "out", false, false, false}, log);
    t.push_back(seconds_since(t0) / points);
    fs::remove_all(dir);
  }
  return median(t);
}

// Seconds per run of the breach model alone on `scene` (kd varied as in the study), median.
double model_alone(const std::string& scene, int points, int repeats) {
  const auto base = suite::breach::Scene::read_complete(suite::config::Config::from_file(scene));
  std::vector<double> t;
  double sink = 0.0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    for (int i = 0; i < points; ++i) {
      auto s = base;
      s.soil.kd = (10.0 + 50.0 * i / (points - 1)) * 1e-6;  // 10..60 cm^3/(N s)
      sink += suite::breach::make_summary(suite::breach::simulate(s)).json().at("peak_outflow").get<double>();
    }
    t.push_back(seconds_since(t0) / points);
  }
  if (!(sink > 0)) std::fprintf(stderr, "no peak outflow\n");
  return median(t);
}

// Wall seconds of the study `spec` with `overrides`, median of `repeats`.
double study_wall(const suite::mpi::Comm& comm, const std::string& spec, const std::vector<std::string>& overrides,
                  int repeats) {
  suite::Logger log(comm, "study", {suite::LogLevel::error, false, nullptr});
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const fs::path dir = fs::temp_directory_path() / ("suite-study-wall-" + std::to_string(getpid()));
    fs::remove_all(dir);
    const auto t0 = Clock::now();
    suite::studies::run_study(suite::config::Config::from_file(spec, overrides), {dir, false, false, false}, log);
    t.push_back(seconds_since(t0));
    fs::remove_all(dir);
  }
  return median(t);
}

std::string csv_header(int repeats, const std::string& what) {
  const auto b = suite::build_info();
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return fmt::format("# study_overhead: host {}, {} cores, suite {} ({}), {}, medians of {} repeats, {}\n", host,
                     sysconf(_SC_NPROCESSORS_ONLN), b.version, b.git_hash, b.build_type, repeats, what);
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm self(MPI_COMM_SELF);
  std::string out_csv, dissertation, wall_csv;
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--out") out_csv = argv[i + 1];
    if (a == "--repeats") repeats = std::stoi(argv[i + 1]);
    if (a == "--dissertation") dissertation = argv[i + 1];
    if (a == "--wall-out") wall_csv = argv[i + 1];
  }
  const std::string common = "execution: {concurrency: 1}\noutput: {plot: false}\n";
  const std::string formula =
      "variables:\n  - {name: x, lower: 0, upper: 1}\n"
      "method: {type: multidim, partitions: 1999}\n"
      "model: {type: expression, responses: {y: \"2*x\"}}\n" +
      common;
  auto breach = [&](const std::string& read_scene) {
    return std::string(
               "variables:\n  - {name: kd, lower: 10, upper: 60}\n"
               "method: {type: multidim, partitions: 199}\n"
               "model:\n  type: breach\n  scene: ") +
           SUITE_BREACH_DEFAULT_SCENE + "\n  read_scene: " + read_scene +
           "\n  set: {soil.erodibility: \"{kd} cm^3/(N s)\"}\n  responses: [peak_outflow]\n" + common;
  };
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
  const std::vector<Row> rows = {
      {"in-process formula", per_evaluation(self, formula, 2000, repeats)},
      {"in-process breach model", per_evaluation(self, breach("once"), 200, repeats)},
      {"in-process breach model (scene read every evaluation)",
       per_evaluation(self, breach("every_evaluation"), 200, repeats)},
      {"breach model alone (no engine)", model_alone(SUITE_BREACH_DEFAULT_SCENE, 200, repeats)},
      {"local process (sh driver)", per_evaluation(self, process, 200, repeats)}};
  for (const auto& r : rows) std::printf("%-52s %10.3f ms per evaluation\n", r.backend, r.seconds * 1e3);
  if (!out_csv.empty()) {
    std::ofstream csv(out_csv);
    csv << csv_header(repeats, "one evaluation at a time") << "backend,seconds_per_evaluation\n";
    for (const auto& r : rows) csv << r.backend << ',' << r.seconds << '\n';
  }
  if (dissertation.empty()) return 0;
  const std::vector<std::string> two = {"execution.concurrency=2"};
  const std::vector<Row> walls = {
      {"216 runs without charts", study_wall(self, dissertation, {two[0], "output.plot=false"}, repeats)},
      {"216 runs without charts (scene read every evaluation)",
       study_wall(self, dissertation, {two[0], "output.plot=false", "model.read_scene=every_evaluation"}, repeats)},
      {"216 runs with charts", study_wall(self, dissertation, two, repeats)}};
  for (const auto& r : walls) std::printf("%-52s %10.3f s\n", r.backend, r.seconds);
  if (!wall_csv.empty()) {
    std::ofstream csv(wall_csv);
    csv << csv_header(repeats, "2 threads, " + fs::path(dissertation).filename().string()) << "case,wall_seconds\n";
    for (const auto& r : walls) csv << r.backend << ',' << r.seconds << '\n';
  }
  return 0;
}
