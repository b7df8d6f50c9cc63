// study: parameter studies over the suite's models (docs/methods/studies.md, issue 6); `study
// --help` lists the commands, `study COMMAND --help` describes one.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/cli/subcommands.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "core/run/shard.hpp"
#include "studies/run/study.hpp"
#include "studies/template/expression.hpp"
#include "studies/template/templatize.hpp"

namespace {

using suite::cli::CommandSpec;
using Option = suite::cli::OptionSpec;

suite::cli::ProgramSpec program_spec() {
  const auto retry = Option::flag("retry-failed", "run again the evaluations that failed");
  return {
      "study",
      "study: parameter studies, uncertainty quantification and sensitivity analysis (docs/studies.md)",
      {
          CommandSpec{"run",
                      "generate the design, evaluate the model at every point, write DIR/tabular.dat and "
                      "tabular.csv (DIR defaults to study-<SPEC name>)",
                      "SPEC.yaml",
                      1,
                      1,
                      true,
                      {Option::text("out", "DIR", "the study folder (created)"), retry}},
          CommandSpec{"resume",
                      "continue a killed study: runs only what its ledger does not hold (and, with --retry-failed, "
                      "what failed); with --shard K/N, array task K of N runs the evaluations with (id - 1) % N == K "
                      "into DIR/ledger.K.jsonl",
                      "DIR",
                      1,
                      1,
                      false,
                      {retry, Option::text("shard", "K/N", "Slurm array task K of N")}},
          CommandSpec{"analyze",
                      "rewrite DIR's tables and analysis.json from its ledger, running nothing",
                      "DIR",
                      1,
                      1,
                      false,
                      {}},
          CommandSpec{"prepare",
                      "check SPEC and write DIR/study.yaml only (before a Slurm array of `study resume DIR --shard`)",
                      "SPEC.yaml",
                      1,
                      1,
                      true,
                      {Option::text("out", "DIR", "the study folder (created)", true)}},
          CommandSpec{"templatize",
                      "write a template of FILE (standard output by default): LOCATION is LINE:FIELD for "
                      "fixed-column text, or a YAML key path (soil.erodibility, items as key[2])",
                      "FILE",
                      1,
                      1,
                      false,
                      {Option::repeated("var", "NAME=LOCATION", "a variable and where its value stands in FILE", true),
                       Option::text("out", "TEMPLATE", "the template file")}},
      }};
}

struct Arguments {
  std::string command, target, out, log_level = "info";
  std::vector<std::string> overrides;
  std::vector<std::pair<std::string, std::string>> vars;  // templatize: NAME, LOCATION
  bool retry_failed = false;
  int shard_index = 0, shard_count = 0;  // --shard K/N
};

Arguments arguments_of(const suite::cli::CommandArguments& c) {
  Arguments a;
  a.command = c.command;
  a.target = c.targets.at(0);
  a.overrides = c.overrides;
  a.out = c.text_or("out", "");
  a.log_level = c.log_level;
  a.retry_failed = c.has("retry-failed");
  for (const auto& v : c.all("var")) {
    const auto eq = v.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
      throw suite::InputError(fmt::format("--var '{}': write NAME=LOCATION, e.g. Kd=12:3 or Kd=soil.erodibility", v));
    a.vars.emplace_back(v.substr(0, eq), v.substr(eq + 1));
  }
  if (c.has("shard")) {
    const suite::Shard shard = suite::parse_shard(c.text_or("shard", ""));
    a.shard_index = shard.index, a.shard_count = shard.count;
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse_command(program_spec(), argc, argv);
    if (!parsed.arguments) {
      if (world.is_root()) std::fputs((parsed.message + "\n").c_str(), parsed.exit_code ? stderr : stdout);
      return parsed.exit_code;
    }
    const Arguments a = arguments_of(*parsed.arguments);
    suite::Logger log(world, "study", {suite::parse_log_level(a.log_level), false, nullptr});
    const bool mpi = world.size() > 1;  // rank 0 hands out evaluations to the other ranks
    if (a.command == "prepare") {
      suite::mpi::collective_try(world, [&] {
        if (world.is_root()) {
          suite::studies::StudyOptions prepare{a.out, false, false, false, nullptr, true};
          suite::studies::run_study(suite::config::Config::from_file(a.target, a.overrides), prepare, log);
        }
      });
      return 0;
    }
    if (a.command == "run") {
      const std::string out = a.out.empty() ? "study-" + std::filesystem::path(a.target).stem().string() : a.out;
      if (!mpi) {
        suite::studies::run_study(suite::config::Config::from_file(a.target, a.overrides), {out, false, a.retry_failed},
                                  log);
        return 0;
      }
      // Rank 0 checks the specification and writes study.yaml (with any seed it drew); then every
      // rank reads that file, so all of them build the same design.
      suite::mpi::collective_try(world, [&] {
        if (world.is_root()) {
          suite::studies::StudyOptions prepare{out, false, false, false, &world, true};
          suite::studies::run_study(suite::config::Config::from_file(a.target, a.overrides), prepare, log);
        }
      });
      suite::studies::StudyOptions o{out, true, a.retry_failed, false, &world, false};
      suite::studies::run_study(suite::config::Config::from_file(std::filesystem::path(out) / "study.yaml"), o, log);
      return 0;
    }
    if (a.command == "resume" || a.command == "analyze") {
      const std::filesystem::path dir = a.target;
      if (!std::filesystem::exists(dir / "study.yaml"))
        throw suite::InputError(fmt::format("'{}' is not a study folder (no study.yaml)", dir.string()));
      const auto spec = suite::config::Config::from_file(dir / "study.yaml");
      suite::studies::StudyOptions o{
          dir,   true,          a.retry_failed, a.command == "analyze", mpi ? &world : nullptr,
          false, a.shard_index, a.shard_count};
      suite::studies::run_study(spec, o, log);
      return 0;
    }
    if (a.command == "templatize") {
      if (!world.is_root()) return 0;
      std::ifstream in(a.target);
      if (!in) throw suite::InputError(fmt::format("cannot read '{}'", a.target));
      std::stringstream text;
      text << in.rdbuf();
      const auto t = suite::studies::templatize(text.str(), a.target, a.vars);
      if (a.out.empty()) {
        std::fputs(t.text.c_str(), stdout);
      } else {
        suite::io::write_file_atomic(a.out, t.text);
      }
      for (const auto& [name, v] : t.values)
        std::fprintf(stderr, "%s = %s (the value in %s)\n", name.c_str(), suite::studies::format_number(v).c_str(),
                     a.target.c_str());
      return 0;
    }
    throw std::logic_error("study: command '" + a.command + "' has no handler");
  });
}
