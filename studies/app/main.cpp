// study: parameter studies over the suite's models (docs/methods/studies.md, issue 6).
//   study run SPEC.yaml [key.path=value ...] [--out DIR] [--log-level LEVEL]
//   study resume DIR [--retry-failed] [--log-level LEVEL]
//   study analyze DIR
//   study templatize FILE --var NAME=LOCATION ... [--out TEMPLATE]
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

constexpr const char* kUsage =
    "usage:\n"
    "  study run SPEC.yaml [key.path=value ...] [--out DIR] [--log-level LEVEL]\n"
    "      generate the design, evaluate the model at every point, write DIR/tabular.dat and tabular.csv\n"
    "      (DIR defaults to study-<SPEC name>)\n"
    "  study resume DIR [--retry-failed] [--log-level LEVEL]\n"
    "      continue a killed study: runs only what its ledger does not hold (and, with --retry-failed,\n"
    "      what failed)\n"
    "  study analyze DIR\n"
    "      rewrite DIR's tables and analysis.json from its ledger, running nothing\n"
    "  study prepare SPEC.yaml [key.path=value ...] --out DIR\n"
    "      check SPEC and write DIR/study.yaml only (before a Slurm array of `study resume DIR --shard`)\n"
    "  study resume DIR --shard K/N\n"
    "      array task K of N: run the evaluations with (id - 1) % N == K into DIR/ledger.K.jsonl\n"
    "  study templatize FILE --var NAME=LOCATION ... [--out TEMPLATE]\n"
    "      write a template of FILE (standard output by default): LOCATION is LINE:FIELD for\n"
    "      fixed-column text, or a YAML key path (soil.erodibility, items as key[2])\n";

struct Arguments {
  std::string command, target, out, log_level = "info";
  std::vector<std::string> overrides;
  std::vector<std::pair<std::string, std::string>> vars;  // templatize: NAME, LOCATION
  bool retry_failed = false;
  int shard_index = 0, shard_count = 0;  // --shard K/N
};

Arguments parse(int argc, char** argv) {
  Arguments a;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) throw suite::InputError(std::string("no command given\n") + kUsage);
  a.command = args[0];
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& s = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw suite::InputError(s + " needs a value");
      return args[++i];
    };
    if (s == "--out") {
      a.out = value();
    } else if (s == "--log-level") {
      a.log_level = value();
    } else if (s == "--var") {
      const std::string v = value();
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
        throw suite::InputError(fmt::format("--var '{}': write NAME=LOCATION, e.g. Kd=12:3 or Kd=soil.erodibility", v));
      a.vars.emplace_back(v.substr(0, eq), v.substr(eq + 1));
    } else if (s == "--shard") {
      const suite::Shard shard = suite::parse_shard(value());
      a.shard_index = shard.index, a.shard_count = shard.count;
    } else if (s == "--retry-failed") {
      a.retry_failed = true;
    } else if (suite::config::looks_like_override(s)) {
      a.overrides.push_back(s);
    } else if (a.target.empty() && s.rfind("--", 0) != 0) {
      a.target = s;
    } else {
      throw suite::InputError(fmt::format("unexpected argument '{}'\n{}", s, kUsage));
    }
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
      if (world.is_root()) std::fputs(kUsage, stdout);
      return 0;
    }
    const Arguments a = parse(argc, argv);
    suite::Logger log(world, "study", {suite::parse_log_level(a.log_level), false, nullptr});
    const bool mpi = world.size() > 1;  // rank 0 hands out evaluations to the other ranks
    if (a.command == "prepare") {
      if (a.target.empty() || a.out.empty())
        throw suite::InputError(std::string("study prepare needs a specification and --out\n") + kUsage);
      suite::mpi::collective_try(world, [&] {
        if (world.is_root()) {
          suite::studies::StudyOptions prepare{a.out, false, false, false, nullptr, true};
          suite::studies::run_study(suite::config::Config::from_file(a.target, a.overrides), prepare, log);
        }
      });
      return 0;
    }
    if (a.command == "run") {
      if (a.target.empty()) throw suite::InputError(std::string("study run needs a specification file\n") + kUsage);
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
      if (a.target.empty()) throw suite::InputError(std::string("study resume needs the study folder\n") + kUsage);
      if (!a.overrides.empty() || !a.out.empty())
        throw suite::InputError("study " + a.command +
                                " takes the study folder only: the specification is its study.yaml");
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
      if (a.target.empty() || a.vars.empty())
        throw suite::InputError(std::string("study templatize needs a file and at least one --var\n") + kUsage);
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
    throw suite::InputError(fmt::format("unknown command '{}'\n{}", a.command, kUsage));
  });
}
