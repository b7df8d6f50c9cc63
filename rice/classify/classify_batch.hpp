#pragma once
// `riceasv classify` as a resumable batch (docs/rice.md, "Batches of thousands of photographs"):
// the photographs (folders expanded, image_files.hpp) are cut, in their order, into parts of
// `part_size`, and each part is classified on its own into DIR/parts/NNNN/ (the tables of
// classify_images.hpp for those photographs), written under NNNN.partial and renamed when complete.
//   - A rerun into the same DIR skips the parts already there: a killed batch loses only the part it
//     was in. DIR/images.txt records the photographs; a rerun with other photographs is an
//     InputError (give another --out).
//   - A Slurm array task takes the parts with index % N == K (--shard K/N).
//   - When every part is there, DIR/classes.csv, results.csv, scores.csv (networks), measure.json,
//     classify.json and crops/ are written from the parts in photograph order (merge_classified), so
//     they read as one run's; otherwise the missing parts are named and `riceasv merge DIR` merges
//     once the other tasks are done.
// Not collective.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/log/logger.hpp"
#include "core/run/shard.hpp"
#include "rice/classify/classify_images.hpp"

namespace suite::rice {

struct BatchOptions {
  int part_size = 50;  // photographs per part
  Shard shard;         // count 0: every part
};

// Classifies the photographs of one part into a folder (classify_images or classify_images_onnx).
using PartClassifier =
    std::function<ClassifySummary(const std::vector<std::filesystem::path>& images, const std::filesystem::path& out)>;

struct BatchSummary {
  int parts = 0;             // in the whole batch
  int done_before = 0;       // found complete and skipped
  int done_now = 0;          // classified by this run
  std::vector<int> missing;  // parts neither found nor classified (other shards)
  ClassifySummary now;       // over the parts this run classified
  bool merged = false;       // DIR's tables written from every part
  ClassifySummary all;       // merged: over the whole batch
};

BatchSummary classify_batch(const std::vector<std::filesystem::path>& targets, const PartClassifier& classify_part,
                            const BatchOptions& options, const std::filesystem::path& out, Logger& log);

// Writes DIR's tables from DIR/parts/*; InputError naming the missing parts (and what to run) unless
// every part of DIR/images.txt is complete. Returns the counts over the whole batch.
ClassifySummary merge_classified(const std::filesystem::path& out);

}  // namespace suite::rice
