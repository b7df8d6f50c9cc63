#pragma once
// Group order of the particles (grid/node_tile.hpp): the transfers fill or read one tile per run
// of consecutive particles of one group, so they are fastest when each group's particles are
// consecutive in memory. Particles drift out of that order as they cross block boundaries, and
// the ones a rank receives or an inlet emits come last; group_order() tells when, and how, to put
// them back. A particle keeps its id (Particles::id) when it moves.
// The order only changes the order of the sums onto the nodes (round-off). It is a function of
// the particles alone (their order and positions), so that a run restarted from a checkpoint,
// which keeps the particles in their order, reorders on the same steps as the uninterrupted run.
#include <cstddef>
#include <vector>

namespace suite::mpm2grid {

// group[p]: particle p's group, as the index of its block (touch_blocks); blocks: how many there
// are. Returns the permutation (new position -> old index) that makes each group's particles
// consecutive, groups in the order of their block indices and the particles of a group in their
// present order (a counting sort); or an empty one when the particles already come in at most a
// quarter more runs than there are groups (then reordering costs more than it saves).
inline std::vector<std::size_t> group_order(const std::vector<int>& group, std::size_t blocks) {
  std::vector<std::size_t> start(blocks + 1, 0);
  std::size_t runs = 0, groups = 0;
  for (std::size_t p = 0; p < group.size(); ++p) {
    if (start[static_cast<std::size_t>(group[p]) + 1]++ == 0) ++groups;
    if (p == 0 || group[p] != group[p - 1]) ++runs;
  }
  if (4 * runs <= 5 * groups) return {};
  for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  std::vector<std::size_t> order(group.size());
  for (std::size_t p = 0; p < group.size(); ++p) order[start[static_cast<std::size_t>(group[p])]++] = p;
  return order;
}

// Reorders values by a permutation from group_order (new position -> old index), keeping the
// array's capacity: reserved to its exact size, every array was copied into one of twice that
// size at the next particle an inlet emitted.
template <class T>
void apply_order(std::vector<T>& values, const std::vector<std::size_t>& order) {
  std::vector<T> out;
  out.reserve(values.capacity());
  for (std::size_t old : order) out.push_back(values[old]);
  values.swap(out);
}

}  // namespace suite::mpm2grid
