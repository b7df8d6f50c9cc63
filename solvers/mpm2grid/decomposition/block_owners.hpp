#pragma once
// Which rank owns each grid block (docs/methods/mpm2grid.md, "Decomposition and performance design"):
// one small table, block key -> rank, the same on every rank. It holds one integer per block
// (never node values): the grid's nodes and the solution live only on the ranks that own or
// border them. The table is set by a partition (decomposition/partition.hpp) and grows between
// partitions by claims: a block that some rank's particles reach for the first time goes to the
// lowest rank that reached it. Blocks that emptied stay in the table until the next partition,
// which keeps only the blocks then in use.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite::mpm2grid {

class BlockOwners {
 public:
  using Key = std::uint64_t;

  // The owning rank, or -1 for a block that has none yet.
  int owner(Key key) const {
    const auto it = owner_.find(key);
    return it == owner_.end() ? -1 : it->second;
  }
  std::size_t size() const { return owner_.size(); }

  // Gives every key some rank named (keys without an owner; repeats allowed) to the lowest rank
  // that named it. Returns how many blocks were added. COLLECTIVE.
  long long claim(const mpi::Comm& comm, const std::vector<Key>& unowned);

  // Replaces the table: keys[i] goes to ranks[i].
  void assign(const std::vector<Key>& keys, const std::vector<int>& ranks);

  // The keys `rank` owns, in increasing order (for checkpoints).
  std::vector<Key> owned_by(int rank) const;
  // Rebuilds the table from every rank's owned_by(rank) (a checkpoint's). COLLECTIVE.
  void restore(const mpi::Comm& comm, const std::vector<Key>& mine);

 private:
  std::unordered_map<Key, int> owner_;
};

}  // namespace suite::mpm2grid
