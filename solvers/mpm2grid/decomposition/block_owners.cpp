#include "solvers/mpm2grid/decomposition/block_owners.hpp"

#include <algorithm>
#include <stdexcept>

#include "solvers/mpm2grid/decomposition/exchange.hpp"

namespace suite::mpm2grid {

long long BlockOwners::claim(const mpi::Comm& comm, const std::vector<Key>& unowned) {
  // Most steps claim nothing: one reduction instead of a gather then.
  if (!comm.any(!unowned.empty())) return 0;
  const auto named = all_gather(comm, unowned);
  long long added = 0;
  for (int r = 0; r < comm.size(); ++r)  // in rank order: the lowest rank wins
    for (const Key k : named[static_cast<std::size_t>(r)]) added += owner_.emplace(k, r).second ? 1 : 0;
  return added;
}

void BlockOwners::assign(const std::vector<Key>& keys, const std::vector<int>& ranks) {
  if (keys.size() != ranks.size()) throw std::invalid_argument("BlockOwners::assign: one rank per key");
  owner_.clear();
  owner_.reserve(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) owner_[keys[i]] = ranks[i];
}

std::vector<BlockOwners::Key> BlockOwners::owned_by(int rank) const {
  std::vector<Key> keys;
  for (const auto& [k, r] : owner_)
    if (r == rank) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  return keys;
}

void BlockOwners::restore(const mpi::Comm& comm, const std::vector<Key>& mine) {
  const auto all = all_gather(comm, mine);
  owner_.clear();
  for (int r = 0; r < comm.size(); ++r)
    for (const Key k : all[static_cast<std::size_t>(r)]) owner_[k] = r;
}

}  // namespace suite::mpm2grid
