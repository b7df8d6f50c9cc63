// Speed and accuracy of the breach model on one core (issue 5's benchmark):
//   1. throughput: library calls on the default scene cut to a 20-hour event, in batches; the
//      median batch gives runs per minute per core (goal: >= 10,000);
//   2. speed versus accuracy: the peak outflow's relative error against a tolerance-1e-11
//      reference, and the time per run, for the adaptive scheme over a range of tolerances and
//      for fixed steps over a range of dt.
//
//   breach_speed_accuracy [--out FILE.csv] [--repeats R] [--batch N]
//
// Timings are medians of R repeats; both series are measured in the same process, so their
// ratio holds on a noisy machine even when absolute times drift.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/run/build_info.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace {

using namespace suite::breach;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Scene scene(const std::vector<std::string>& overrides) {
  std::vector<std::string> o = {"time.end=20 h"};
  o.insert(o.end(), overrides.begin(), overrides.end());
  auto cfg = suite::config::Config::from_file(SUITE_BREACH_DEFAULT_SCENE, o);
  return Scene::read(cfg.root());
}

// Median seconds per run over `repeats` batches of `batch` runs.
double seconds_per_run(const Scene& s, int repeats, int batch, Result& last) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < batch; ++i) last = simulate(s);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / batch);
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_csv;
  int repeats = 5, batch = 2000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--out") out_csv = argv[i + 1];
    if (a == "--repeats") repeats = std::stoi(argv[i + 1]);
    if (a == "--batch") batch = std::stoi(argv[i + 1]);
  }
  Result r;
  const double per_run = seconds_per_run(scene({}), repeats, batch, r);
  std::printf(
      "default scene, 20-hour event, tolerance 1e-6: %.3f ms per run = %.0f runs per minute per core "
      "(median of %d batches of %d; %ld steps, %ld evaluations)\n",
      per_run * 1e3, 60.0 / per_run, repeats, batch, r.steps, r.evaluations);

  const double reference = simulate(scene({"time.tolerance=1e-11"})).peak_outflow;
  struct Row {
    std::string method;
    double parameter, seconds, error;
    long evaluations;
  };
  std::vector<Row> rows;
  for (double tol : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    const Scene s = scene({"time.tolerance=" + fmt::format("{}", tol)});
    const double sec = seconds_per_run(s, repeats, std::max(1, batch / 10), r);
    rows.push_back({"adaptive", tol, sec, std::abs(r.peak_outflow / reference - 1.0), r.evaluations});
  }
  for (double dt : {3600.0, 1800.0, 900.0, 600.0, 300.0, 120.0, 60.0, 30.0, 10.0}) {
    const Scene s = scene({"time.step=fixed", "time.dt=" + fmt::format("{}", dt) + " s"});
    const double sec = seconds_per_run(s, repeats, std::max(1, batch / 100), r);
    rows.push_back({"fixed", dt, sec, std::abs(r.peak_outflow / reference - 1.0), r.evaluations});
  }
  std::printf("%-9s %12s %12s %12s %12s\n", "method", "tol or dt", "ms per run", "peak error", "evaluations");
  for (const Row& row : rows)
    std::printf("%-9s %12g %12.4f %12.3e %12ld\n", row.method.c_str(), row.parameter, row.seconds * 1e3, row.error,
                row.evaluations);
  if (!out_csv.empty()) {
    const auto b = suite::build_info();
    char host[256] = {0};
    gethostname(host, sizeof host - 1);
    std::ofstream csv(out_csv);
    csv << "# breach_speed_accuracy: host " << host << ", " << sysconf(_SC_NPROCESSORS_ONLN) << " cores, suite "
        << b.version << " (" << b.git_hash << "), " << b.build_type << ", " << b.compiler << ", medians of " << repeats
        << " repeats\n";
    csv << "# throughput: " << per_run * 1e3 << " ms per run, " << 60.0 / per_run
        << " runs per minute per core (default scene, 20-hour event, tolerance 1e-6)\n";
    csv << "# reference peak outflow (tolerance 1e-11): " << reference << " m^3/s\n";
    csv << "method,parameter,seconds_per_run,peak_relative_error,evaluations\n";
    for (const Row& row : rows)
      csv << row.method << ',' << row.parameter << ',' << row.seconds << ',' << row.error << ',' << row.evaluations
          << '\n';
  }
  return 0;
}
