#pragma once
// Group order of the particles (grid/node_tile.hpp): the transfers fill or read one tile per run
// of consecutive particles of one group, so they are fastest when each group's particles are
// consecutive in memory. Particles drift out of that order as they cross block boundaries, the
// ones a rank receives or an inlet emits come last, and the last ones fill the places of those
// that leave (Particles::remove); group_order() tells when, and how, to put them back. A particle
// keeps its id (Particles::id) when it moves.
// The order only changes the order of the sums onto the nodes (round-off). It is a function of
// the particles alone (their order and positions), so that a run restarted from a checkpoint,
// which keeps the particles in their order, reorders on the same steps as the uninterrupted run.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <vector>

namespace suite::mpm2grid {

// group[p]: particle p's group, as the index of its block (touch_blocks); blocks: how many there
// are. Returns the permutation (new position -> old index) that makes each group's particles
// consecutive, groups in the order of their block indices and the particles of a group in their
// present order (a counting sort); or an empty one when the particles already come in at most
// twice as many runs as there are groups. Reordering copies every particle; an extra run costs
// a tile's load and flush in each transfer. Late in example 2 (h = 0.1 m, 60k water particles,
// 10.0 -> 10.6 s, one thread) an extra run cost 0.18 us a step and a reordering of the water
// 1.4 ms, with some 180 runs more each step: the step's cost of both is flat between 2 and 3
// runs per group (0.34 and 0.35 ms, against 0.83 ms at the 1.25 used before; step 4.4% faster
// at 2). `threads` count the runs and groups. With `rank`, the groups go in the order of
// rank[group] instead of their indices (a permutation of 0 .. blocks - 1: sweep_schedule.hpp's
// colour order).
inline std::vector<std::size_t> group_order(const std::vector<int>& group, std::size_t blocks, int threads = 1,
                                            const std::vector<int>* rank = nullptr) {
  // A group's first particle starts a run: marking the groups of the runs' first particles finds
  // every group.
  std::vector<char> seen(blocks, 0);
  const std::size_t n = group.size();
  std::size_t runs = 0;
#pragma omp parallel for schedule(static) reduction(+ : runs) num_threads(threads) if (threads > 1)
  for (std::size_t p = 0; p < n; ++p)
    if (p == 0 || group[p] != group[p - 1]) {
      ++runs;
      std::atomic_ref<char>(seen[static_cast<std::size_t>(group[p])]).store(1, std::memory_order_relaxed);
    }
  const auto groups = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 1));
  if (runs <= 2 * groups) return {};
  const auto place = [&](std::size_t p) {
    return static_cast<std::size_t>(rank ? (*rank)[static_cast<std::size_t>(group[p])] : group[p]);
  };
  std::vector<std::size_t> start(blocks + 1, 0);
  for (std::size_t p = 0; p < n; ++p) ++start[place(p) + 1];
  for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  std::vector<std::size_t> order(n);
  for (std::size_t p = 0; p < n; ++p) order[start[place(p)]++] = p;
  return order;
}

// Reorders values by a permutation from group_order (new position -> old index), keeping the
// array's capacity: reserved to its exact size, every array was copied into one of twice that
// size at the next particle an inlet emitted. `threads` share the copies.
template <class T>
void apply_order(std::vector<T>& values, const std::vector<std::size_t>& order, int threads = 1) {
  std::vector<T> out;
  out.reserve(values.capacity());
  if (threads == 1) {
    for (std::size_t old : order) out.push_back(values[old]);
  } else {
    out.resize(order.size());
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t i = 0; i < order.size(); ++i) out[i] = values[order[i]];
  }
  values.swap(out);
}

}  // namespace suite::mpm2grid
