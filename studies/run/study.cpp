#include "studies/run/study.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include "core/dakota/tabular_file.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "core/run/run_record.hpp"
#include "studies/analysis/report.hpp"
#include "studies/design/parameter_studies.hpp"
#include "studies/ledger/ledger.hpp"
#include "studies/model/model.hpp"
#include "studies/plot/plot_command.hpp"
#include "studies/run/mpi_workers.hpp"
#include "studies/template/expression.hpp"

namespace suite::studies {

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

namespace {

// The latest entry of each evaluation in the ledger.
// The latest entry of each evaluation over the ledger and its shards (ledger.<task>.jsonl of
// Slurm array tasks): a successful entry wins over a failed one, then the later file.
std::map<long, LedgerEntry> latest(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files{dir / "ledger.jsonl"};
  std::vector<std::filesystem::path> shards;
  std::error_code ec;
  for (const auto& f : std::filesystem::directory_iterator(dir, ec)) {
    const auto name = f.path().filename().string();
    if (name.rfind("ledger.", 0) == 0 && name != "ledger.jsonl" && f.path().extension() == ".jsonl")
      shards.push_back(f.path());
  }
  std::sort(shards.begin(), shards.end());
  files.insert(files.end(), shards.begin(), shards.end());
  std::map<long, LedgerEntry> by_id;
  for (const auto& file : files)
    for (auto& e : Ledger::read(file)) {
      auto it = by_id.find(e.eval_id);
      if (it == by_id.end() || e.ok || !it->second.ok) by_id[e.eval_id] = std::move(e);
    }
  return by_id;
}

void write_tables(const std::filesystem::path& out, const std::vector<std::string>& vars,
                  const std::vector<std::string>& responses, const std::map<long, LedgerEntry>& entries) {
  std::ostringstream dat;
  {
    dakota::TabularWriter tab(dat, vars, responses);
    for (const auto& [id, e] : entries)
      if (e.ok) tab.row(id, "", e.inputs, e.responses);
  }
  io::write_file_atomic(out / "tabular.dat", dat.str());
  std::string csv = fmt::format("eval_id,status,{},{},reason\n", fmt::join(vars, ","), fmt::join(responses, ","));
  for (const auto& [id, e] : entries) {
    csv += fmt::format("{},{}", id, e.ok ? "ok" : "failed");
    for (double x : e.inputs) fmt::format_to(std::back_inserter(csv), ",{}", format_number(x));
    for (double x : e.responses)
      fmt::format_to(std::back_inserter(csv), ",{}", std::isfinite(x) ? fmt::format("{:.17g}", x) : "");
    fmt::format_to(std::back_inserter(csv), ",{}\n", io::csv_field(e.reason));
  }
  io::write_file_atomic(out / "tabular.csv", csv);
}

// Every template rendered with each variable at its median and checked against the model before
// anything runs: a misspelt key, a wrong unit or a template Python would reject stops the study
// here (exit 2) instead of failing every evaluation. The median is the value least likely to be
// out of the model's range; a value that only some points take still fails just those points.
void check_model(const Model& model, const std::vector<Variable>& variables, const std::string& source) {
  std::map<std::string, double> values;
  std::vector<std::string> shown;
  for (const auto& v : variables) {
    values[v.name] = quantile(v.distribution, 0.5);
    shown.push_back(fmt::format("{} = {}", v.name, format_number(values[v.name])));
  }
  try {
    model.check(values);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: the model rejects the study's inputs before any evaluation (checked with every "
                                 "variable at its median: {}): {}",
                                 source, fmt::join(shown, ", "), e.what()));
  }
}

}  // namespace

StudyCounts run_study(const config::Config& spec, const StudyOptions& options, Logger& log) {
  const auto root = spec.root();
  const auto variables = read_variables(root);
  const auto var_names = names(variables);
  const Design design = read_design(root.section("method"), variables);
  const auto model = read_model(root.section("model"), var_names, options.out);
  const auto execution = root.section_or_empty("execution");
  const bool plot = root.section_or_empty("output").get<bool>("plot", true);
  const int cores = available_cores();
  // Not written into study.yaml when absent: a resume on another allocation uses its own cores.
  const int concurrency =
      execution.has("concurrency") ? static_cast<int>(execution.integer("concurrency", cores, 1, 4096)) : cores;
  spec.finish();
  check_model(*model, variables, spec.source_name());

  const bool distributed = options.comm && options.comm->size() > 1;
  const bool writer = !distributed || options.comm->is_root();  // the rank that writes files
  const auto out = std::filesystem::absolute(options.out);      // work directories are entered by programs
  const auto ledger_path = out / "ledger.jsonl";
  if (writer) {
    std::filesystem::create_directories(out);
    if (!options.resume && std::filesystem::exists(ledger_path))
      throw InputError(
          fmt::format("'{}' already holds a study (ledger.jsonl); continue it with `study resume {}` or "
                      "choose another --out",
                      out.string(), out.string()));
    if (!options.resume) spec.write_effective(out / "study.yaml");
  }
  StudyCounts counts;
  counts.points = design.points.size();
  if (options.prepare_only) return counts;

  // Opening the ledger for appending repairs a line torn by a kill; `analyze` only reads it.
  std::optional<Ledger> ledger;
  const bool sharded = options.shard_count > 0;
  if (writer && !options.analyze_only)
    ledger.emplace(sharded ? out / fmt::format("ledger.{}.jsonl", options.shard_index) : ledger_path);
  auto done = writer ? latest(out) : std::map<long, LedgerEntry>{};
  for (const auto& [id, e] : done) {
    if (id < 1 || static_cast<std::size_t>(id) > design.points.size())
      throw InputError(
          fmt::format("{}: evaluation {} is not a point of the study's design ({} points); the design "
                      "changed since the ledger was written (start a new study folder)",
                      ledger_path.string(), id, design.points.size()));
    if (e.responses.size() != model->responses().size())
      throw InputError(
          fmt::format("{}: evaluation {} has {} responses, the study now asks for {}; the responses "
                      "changed since the ledger was written (start a new study folder)",
                      ledger_path.string(), id, e.responses.size(), model->responses().size()));
  }
  std::vector<long> pending;
  for (std::size_t i = 0; i < design.points.size(); ++i) {
    const long id = static_cast<long>(i) + 1;
    const auto it = done.find(id);
    if (it != done.end()) {
      if (it->second.hash != input_hash(var_names, design.points[i]))
        throw InputError(
            fmt::format("{}: evaluation {} was run with other inputs than the study now gives; the "
                        "design changed since the ledger was written (start a new study folder)",
                        ledger_path.string(), id));
      if (it->second.ok || !options.retry_failed) {
        ++counts.reused;
        continue;
      }
    }
    if (!sharded || (id - 1) % options.shard_count == options.shard_index) pending.push_back(id);
  }
  if (options.analyze_only) pending.clear();
  const int threads = std::max(1, std::min<int>(concurrency, static_cast<int>(pending.size())));
  if (distributed)
    log.info("{} study: {} points, {} to run ({} from the ledger), on {} worker ranks", design.method, counts.points,
             pending.size(), counts.reused, options.comm->size() - 1);
  else
    log.info("{} study: {} points, {} to run ({} from the ledger), {} at a time{}", design.method, counts.points,
             pending.size(), counts.reused, threads, concurrency > cores ? " (more than the cores available)" : "");

  // One evaluation, wherever it runs; its record, on the writing rank.
  const std::string host = host_name();
  auto evaluate_one = [&](long id) {
    const auto& x = design.points[static_cast<std::size_t>(id - 1)];
    std::map<std::string, double> values;
    for (std::size_t i = 0; i < x.size(); ++i) values[var_names[i]] = x[i];
    const auto t0 = std::chrono::steady_clock::now();
    RemoteOutcome r{id, model->evaluate(id, values), 0.0, host};
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  std::mutex mutex;
  std::size_t finished = 0, failed = 0;
  auto record = [&](const RemoteOutcome& r) {
    const auto& x = design.points[static_cast<std::size_t>(r.eval_id - 1)];
    const std::lock_guard lock(mutex);
    ledger->append({r.eval_id, x, input_hash(var_names, x), r.outcome.ok, r.outcome.reason, r.outcome.responses,
                    r.wall_s, r.host});
    ++finished;
    if (!r.outcome.ok) {
      ++failed;
      log.warn("evaluation {} failed: {}", r.eval_id, r.outcome.reason);
    }
    if (finished % std::max<std::size_t>(1, pending.size() / 10) == 0 || finished == pending.size())
      log.info("{} / {} evaluations done ({} failed)", finished, pending.size(), failed);
  };

  if (distributed) {
    run_mpi_workers(*options.comm, pending, evaluate_one, record);
    if (!writer) return counts;
  } else {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    auto worker = [&] {
      try {
        for (std::size_t k; (k = next++) < pending.size();) record(evaluate_one(pending[k]));
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        next = pending.size();
      }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
  }

  if (sharded) {  // one array task of several: its shard is written; `study analyze` merges
    log.info("array task {} of {}: {} evaluations done", options.shard_index, options.shard_count, finished);
    counts.run = finished;
    return counts;
  }
  const auto all = latest(out);
  write_tables(out, var_names, model->responses(), all);
  write_json_atomic(out / "analysis.json", analyze(design, var_names, model->responses(), all));
  if (plot) {
    const std::string cmd = plot_command(out);
    if (std::system(cmd.c_str()) != 0) log.warn("the charts failed (command: {}); the tables are complete", cmd);
  }
  counts.run = finished;
  const LedgerEntry* first_failure = nullptr;
  for (const auto& [id, e] : all)
    if (!e.ok) {
      ++counts.failed;
      if (!first_failure) first_failure = &e;
    }
  log.info("study done: {} evaluations, {} failed; {}", all.size(), counts.failed, (out / "tabular.dat").string());
  // A study none of whose evaluations ran has no result to analyse: most often one mistake (a
  // misspelt key in `set`, a unit, a template value) that every evaluation repeats.
  if (!all.empty() && counts.failed == all.size())
    throw InputError(fmt::format("every one of the {} evaluations failed; the first (evaluation {}): {}", all.size(),
                                 first_failure->eval_id, first_failure->reason));
  return counts;
}

}  // namespace suite::studies
