#pragma once
// A study from its specification to its table (docs/methods/studies.md):
//
//   variables: [...]            design/variables.hpp
//   method:    {type: ...}      design/parameter_studies.hpp
//   model:     {type: breach}   model/breach_model.hpp
//   execution: {concurrency: N} default: the cores this process may use (its CPU affinity,
//                               which Slurm and mpiexec set from the allocation); under mpiexec
//                               with several ranks, one evaluation per worker rank instead
//
// writes into the study folder
//   study.yaml          the specification as run (defaults included); `study resume` reads it
//   ledger.jsonl        every evaluation as it ends (ledger/ledger.hpp); array tasks write
//                       ledger.<task>.jsonl shards, read together with it
//   tabular.dat         Dakota's annotated tabular format, successful evaluations in id order
//   tabular.csv         every evaluation: eval_id, status, variables, responses, reason
//   analysis.json       statistics, correlations, regression, Sobol indices, Morris effects
//                       (analysis/report.hpp)
// A failed evaluation is recorded with its reason and never stops the others. A resumed study
// reruns nothing that finished (and, with retry_failed, reruns what failed).
#include <filesystem>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"

namespace suite::studies {

struct StudyOptions {
  std::filesystem::path out;
  bool resume = false;
  bool retry_failed = false;
  bool analyze_only = false;  // `study analyze`: rebuild the tables and analysis.json, run nothing
  // With a communicator of several ranks, rank 0 hands out evaluations to the others and alone
  // writes files (run/mpi_workers.hpp); every rank must have read the same specification (the
  // folder's study.yaml, written by a prepare_only call on rank 0). COLLECTIVE then.
  const mpi::Comm* comm = nullptr;
  bool prepare_only = false;  // check the specification and folder, write study.yaml, stop
  // A Slurm array task: run the evaluations with (id - 1) % shard_count == shard_index into the
  // ledger shard ledger.<index>.jsonl and write no tables (`study analyze` merges the shards).
  int shard_index = 0, shard_count = 0;
};

struct StudyCounts {
  std::size_t points = 0, reused = 0, run = 0, failed = 0;
};

// Throws InputError for a bad specification or a folder that holds another study.
StudyCounts run_study(const config::Config& spec, const StudyOptions& options, Logger& log);

// Cores this process may run on (sched_getaffinity), at least 1.
int available_cores();

}  // namespace suite::studies
