#pragma once
// A Slurm array task's share of a list of work items: `--shard K/N` takes every item whose index
// i satisfies i % N == K (studies' evaluations, seedcarve's seeds).
#include <string>

namespace suite {

struct Shard {
  int index = 0;
  int count = 0;  // 0: no shard (all items)
};

// Parses "K/N" with 0 <= K < N; InputError naming `flag` and the value otherwise.
Shard parse_shard(const std::string& value, const std::string& flag = "--shard");

}  // namespace suite
