// External programs as study models, the way Dakota runs analysis drivers: a shell driver that
// reads Dakota's parameters file and writes a results file; failures of every kind (exit
// status, time limit, missing or unusable results, a driver reporting FAIL) recorded without
// stopping the others; and the breach executable run from a scene template giving the same
// responses as the in-process breach model.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "studies/ledger/ledger.hpp"
#include "studies/run/study.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
namespace fs = std::filesystem;

using suite::testing::read_file;

StudyCounts run_file(const fs::path& spec, const fs::path& out) {
  const suite::mpi::Comm self(MPI_COMM_SELF);
  suite::Logger log(self, "study", {suite::LogLevel::error, false, nullptr});
  auto cfg = suite::config::Config::from_file(spec, {"output.plot=false"});
  return run_study(cfg, {out, false, false}, log);
}

void write_executable(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  ::chmod(p.c_str(), 0755);
}

TEST(CommandModel, DakotaDriverAndItsFailures) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  // y = x1 + 2 x2 from Dakota's standard parameters file (values on lines 2 and 3); the driver
  // misbehaves on purpose at some points, chosen by x1.
  write_executable(dir / "driver.sh", R"X(#!/bin/sh
x1=$(awk 'NR==2 {print $1}' "$1"); x2=$(awk 'NR==3 {print $1}' "$1")
case "$x1" in
  1.0*E+00|1.0*e+00) exit 3 ;;                    # x1 = 1: crashes
esac
k=$(awk -v a="$x1" 'BEGIN {print int(a * 4 + 0.5)}')
if [ "$k" = 1 ] && [ "$(awk -v b="$x2" 'BEGIN {print (b > 1.5)}')" = 1 ]; then   # hangs, and exits 0 on TERM
  trap 'echo 1 y > "$2"; exit 0' TERM; sleep 30 & wait; fi
if [ "$k" = 2 ] && [ "$(awk -v b="$x2" 'BEGIN {print (b > 1.5)}')" = 1 ]; then echo FAIL > "$2"; exit 0; fi
if [ "$k" = 3 ] && [ "$(awk -v b="$x2" 'BEGIN {print (b > 1.5)}')" = 1 ]; then exit 0; fi                 # no results
awk -v a="$x1" -v b="$x2" 'BEGIN {printf "%.17g y\n", a + 2 * b}' > "$2"
)X");
  std::ofstream(dir / "study.yaml") << R"X(variables:
  - {name: x1, lower: 0, upper: 1}
  - {name: x2, lower: 0, upper: 2}
method: {type: multidim, partitions: [4, 1]}
model:
  type: command
  command: [./driver.sh, params.in, results.out]
  parameters_file: {name: params.in, format: standard}
  results: {file: results.out}
  responses: [y]
  time_limit: 1 s
execution: {concurrency: 2}
)X";
  const auto c = run_file(dir / "study.yaml", dir / "out");
  // 5 x 2 points; x1 = 1 crashes (2), and at x2 = 2: x1 = 0.25 hangs, 0.5 reports FAIL, 0.75
  // writes nothing.
  EXPECT_EQ(c.points, 10u);
  EXPECT_EQ(c.failed, 5u);
  std::map<long, LedgerEntry> byid;
  for (auto& e : Ledger::read(dir / "out" / "ledger.jsonl")) byid[e.eval_id] = e;
  for (const auto& [id, e] : byid) {
    if (!e.ok) continue;
    EXPECT_DOUBLE_EQ(e.responses[0], e.inputs[0] + 2 * e.inputs[1]) << id;
  }
  EXPECT_NE(byid[5].reason.find("exited with status 3"), std::string::npos) << byid[5].reason;
  EXPECT_NE(byid[7].reason.find("time limit of 1 s"), std::string::npos) << byid[7].reason;
  EXPECT_LT(byid[7].wall_s, 10.0) << "the hung driver was killed";
  EXPECT_NE(byid[8].reason.find("reports a failed evaluation"), std::string::npos) << byid[8].reason;
  EXPECT_NE(byid[9].reason.find("wrote no"), std::string::npos) << byid[9].reason;
  // The parameters file in each work directory is Dakota's.
  const std::string params = read_file(dir / "out" / "workdir.2" / "params.in");
  // 21 spaces, then the count right-aligned in a field of 22 (Dakota's layout).
  EXPECT_EQ(params.rfind(std::string(42, ' ') + "2 variables\n", 0), 0u) << params;
  EXPECT_NE(params.find(" eval_id\n"), std::string::npos);
}

TEST(CommandModel, BreachExecutableMatchesTheInProcessModel) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  // The default scene as a template in block style (flow-style braces would read as tags).
  std::ofstream(dir / "dam.tmpl") << R"X(dam:
  height: 12 m
  crest_width: 6 m
  crest_length: 150 m
  upstream_slope: 3
  downstream_slope: 3
soil:
  erodibility: {kd} cm^3/(N s)
  critical_shear_stress: 0.1 psf
  undrained_shear_strength: 200 psf
  unit_weight: 120 lbf/ft^3
reservoir:
  storage:
    type: power_law
    alpha: 34722
    exponent: 2
  initial_level: 11 m
inflow:
  type: triangular
  peak: 800 m^3/s
  time_to_peak: 6 h
  duration: 20 h
time:
  end: 24 h
output:
  plot: false
)X";
  // The in-process model's scene: the template with a value where the tag is (`set` replaces it).
  std::string scene = read_file(dir / "dam.tmpl");
  scene.replace(scene.find("{kd}"), 4, "10");
  std::ofstream(dir / "dam.yaml") << scene;
  const std::string common = R"X(variables:
  - {name: kd, lower: 10, upper: 60}
method: {type: multidim, partitions: 2}
)X";
  std::ofstream(dir / "external.yaml") << common << R"X(model:
  type: command
  command: ["{bindir}/breach", dam.yaml, --out, run, --log-level, warn]
  templates: [{file: dam.tmpl, to: dam.yaml}]
  results: {file: run/summary.json, format: summary}
  responses: [peak_outflow, breach_initiation_time]
)X";
  std::ofstream(dir / "inprocess.yaml") << common << R"X(model:
  type: breach
  scene: dam.yaml
  set: {soil.erodibility: "{kd} cm^3/(N s)"}
  responses: [peak_outflow, breach_initiation_time]
)X";
  ASSERT_EQ(run_file(dir / "external.yaml", dir / "ext").failed, 0u) << read_file(dir / "ext" / "tabular.csv");
  ASSERT_EQ(run_file(dir / "inprocess.yaml", dir / "inp").failed, 0u);
  // The executable steps onto its output rows and the library call does not, so the two agree to
  // the integrator's stated step independence (1e-4, docs/breach.md), not bit for bit.
  const auto ext = Ledger::read(dir / "ext" / "ledger.jsonl"), inp = Ledger::read(dir / "inp" / "ledger.jsonl");
  ASSERT_EQ(ext.size(), 3u);
  ASSERT_EQ(inp.size(), 3u);
  std::map<long, LedgerEntry> by_id;
  for (const auto& e : inp) by_id[e.eval_id] = e;
  for (const auto& e : ext)
    for (std::size_t i = 0; i < e.responses.size(); ++i)
      EXPECT_NEAR(e.responses[i], by_id[e.eval_id].responses[i], 1e-4 * std::abs(e.responses[i])) << e.eval_id;
}

}  // namespace
