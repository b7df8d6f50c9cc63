#pragma once
// A seed batch (docs/methods/carving.md, "Batch"): every seed of a manifest measured with its profile,
// one results row per seed streamed to <out>/results.csv as it finishes.
//
// - One process measures the seeds in order. Under MPI, rank 0 hands seeds out one at a time to
//   ranks 1..N-1 as they finish (long and short seeds balance themselves) and writes the table.
// - A rerun into the same folder skips seeds that already have a row (and, with retry_failed,
//   measures failed ones again); a kill loses only the seeds being measured.
// - A bad, missing or empty image, or a seed without a plausible contour, fails that seed's row
//   with the reason; the batch goes on. A bad manifest or profile stops it before any seed.
// - A batch into a folder that holds other seeds adds its seeds to them (batch/seed_register.hpp):
//   the table keeps every seed's row, in the order the seeds were first given.
// - Slurm array tasks: shard K of N measures the seeds with index % N == K into results.K.csv;
//   merge_batch() then writes results.csv from the shards in manifest order.
#include <cstddef>
#include <filesystem>

#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"

namespace suite::carving {

struct BatchOptions {
  std::filesystem::path manifest;
  std::filesystem::path out;
  std::filesystem::path profile;  // for seeds whose row names none
  bool retry_failed = false;
  int shard_index = 0, shard_count = 0;  // shard_count 0: not an array task
  const mpi::Comm* comm = nullptr;       // size >= 2: rank 0 hands out seeds; nullptr: this process only
};

struct BatchCounts {
  std::size_t seeds = 0;     // in the manifest (in this shard)
  std::size_t skipped = 0;   // already in the results table
  std::size_t measured = 0;  // this run
  std::size_t failed = 0;    // this run
};

// COLLECTIVE over options.comm when given. Counts are complete on rank 0.
BatchCounts run_batch(const BatchOptions& options, Logger& log);

// results.csv from results.csv and every results.K.csv in `out`, in the register's order (the
// ids in out/seeds.txt), the newest row of each seed winning.
void merge_batch(const std::filesystem::path& out);

}  // namespace suite::carving
