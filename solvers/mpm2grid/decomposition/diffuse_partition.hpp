#pragma once
// Rebalancing an existing partition of the grid blocks by moving blocks across the parts'
// borders (diffusion), in place of a fresh METIS partition (partition.hpp). A fresh partition
// of a slightly unbalanced graph is a different partition: at 16 ranks example 2's one
// rebalance moved half of its particles, and METIS's time on rank 0 grows with the parts. Here:
//  1. per balanced species, the flow between neighbouring parts that levels the loads with the
//     least total squared flow: the potentials x of the part graph's Laplacian, L x = load - mean,
//     with flow x_p - x_q from part p to its neighbour q (Hu and Blake 1999, "An improved
//     diffusion algorithm for dynamic load balancing", Parallel Computing 25);
//  2. per pair of neighbouring parts, blocks on their border move one at a time, each the one
//     that best keeps the parts compact among those that bring the pair's two-species flow
//     closer to the wanted one; steps 1-2 repeat from the new loads until balanced;
//  3. a refinement: a border block with more neighbours in another part than in its own goes
//     there when that part stays within the target (fewer cut edges, fewer halo blocks).
// Only blocks at borders move, so a rebalance moves a few per cent of the particles.
#include <array>
#include <optional>
#include <vector>

#include "solvers/mpm2grid/decomposition/partition.hpp"

namespace suite::mpm2grid {

struct Diffused {
  std::vector<int> part;  // every block's part
  double imbalance = 1;   // the largest load over the mean, over the balanced species
  long long moved = 0;    // blocks whose part changed (blocks without one before not counted)
};

// `previous[i]`: block i's part (-1: none yet; such blocks join a neighbouring part first).
// weights[i] = {soil, water} particles in block i. A species is balanced where it has at least
// 64 particles a part (as the load check measures), aiming at `target` times its mean or, where
// its largest block is more than twice that margin, at half that block above the mean (blocks
// move whole). Returns nothing when some species stays above `accept` (or that aim, if more)
// after the rounds (a part without neighbours, loads too lumpy to move): the caller partitions
// afresh. Deterministic. Throws LibraryError on inconsistent input (sizes, parts out of range).
std::optional<Diffused> diffuse_partition(const BlockGraph& graph, const std::vector<std::array<long long, 2>>& weights,
                                          const std::vector<int>& previous, int parts, double target, double accept);

}  // namespace suite::mpm2grid
