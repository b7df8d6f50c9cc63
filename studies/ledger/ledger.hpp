#pragma once
// The append-only record of a study's evaluations (docs/methods/studies.md, "Reliability"): one JSON
// object per line in <study>/ledger.jsonl, written and flushed to disk as each evaluation ends,
// so a killed study loses at most the evaluations that were running.
//
// (fsynced at most once a second and on close, so a node failure loses at most the last second).
//
//   {"eval_id": 17, "inputs": [..], "hash": "9f2c...", "status": "ok" | "failed",
//    "reason": "", "responses": [..], "wall_s": 0.0008, "host": "node12"}
//
// A resumed study reads it back and runs only what has no "ok" line (and, with --retry-failed,
// what failed). The hash of the inputs guards against resuming with a changed design.
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/append_log.hpp"

namespace suite::studies {

struct LedgerEntry {
  long eval_id = 0;
  std::vector<double> inputs;
  std::string hash;
  bool ok = false;
  std::string reason;  // why it failed
  std::vector<double> responses;
  double wall_s = 0.0;
  std::string host;
};

// FNV-1a over the variable names and the values' exact bits (hex).
std::string input_hash(const std::vector<std::string>& names, const std::vector<double>& values);

class Ledger {
 public:
  explicit Ledger(std::filesystem::path path);  // opens for appending (creates it)

  void append(const LedgerEntry& e);  // one line, flushed
  // Every entry of an existing ledger, in file order; a torn last line (a kill mid-write) is
  // ignored, any other bad line is an InputError naming the line.
  static std::vector<LedgerEntry> read(const std::filesystem::path& path);

 private:
  io::AppendLog log_;
};

}  // namespace suite::studies
