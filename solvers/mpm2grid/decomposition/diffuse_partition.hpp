#pragma once
// Rebalancing an existing partition of the grid blocks by moving blocks across the parts'
// borders (diffusion), in place of a fresh METIS partition (partition.hpp). A fresh partition
// of a slightly unbalanced graph is a different partition: at 16 ranks example 2's one
// rebalance moved half of its particles, and METIS's time on rank 0 grows with the parts. Here:
//  1. per balanced quantity (partition.hpp), the flow between neighbouring parts that levels
//     the loads with the least total squared flow: the potentials x of the part graph's
//     Laplacian, L x = load - mean, with flow x_p - x_q from part p to its neighbour q (Hu and
//     Blake 1999, "An improved diffusion algorithm for dynamic load balancing", Parallel
//     Computing 25);
//  2. per pair of neighbouring parts, blocks on their border move one at a time, each the one
//     that best keeps the parts compact among those that bring the pair's flows closer to the
//     wanted ones; steps 1-2 repeat from the new loads until balanced;
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
  double imbalance = 1;   // the largest load over the mean, over the balanced quantities
  long long moved = 0;    // blocks whose part changed (blocks without one before not counted)
};

// `previous[i]`: block i's part (-1: none yet; such blocks join a neighbouring part first).
// weights[i]: block i's work (partition.hpp). A quantity is balanced where it has at least 64
// particles a part (as the load check measures), aiming at `target` times its mean (at least its
// tolerance, partition.hpp's kTolerance) or, where
// its largest block is more than twice that margin, at half that block above the mean (blocks
// move whole). Returns nothing when some quantity stays above `accept` (or that aim, if more)
// after the rounds (a part without neighbours, loads too lumpy to move, wet soil in a corner of
// the parts' graph that no border carries it out of): the caller partitions afresh. Deterministic. Throws LibraryError
// on inconsistent input (sizes, parts out of range).
std::optional<Diffused> diffuse_partition(const BlockGraph& graph, const std::vector<BlockWeight>& weights,
                                          const std::vector<int>& previous, int parts, double target, double accept);

// A fresh partition of the blocks (partition_blocks) with every quantity within its tolerance
// (partition.hpp's kTolerance) of its mean plus one block, where a quantity has at least 64
// particles a part. With the wet soil as a third constraint METIS's k-way partition can miss
// the particles' tolerance (a 64 x 32 strip of soil under water with a wet row between, 16
// parts: the soil 16% above its mean, where 4-column slabs balance all three): its parts are
// then diffused (`target`, `accept` as above); where that fails too, METIS's recursive
// bisection is tried the same way (within the tolerances on that strip; on example 2 at
// h = 0.025 m on 16 ranks the k-way's parts are, the bisection's not), and where neither
// serves, the blocks are partitioned without the wet soil (the particles' balance comes
// first). Deterministic.
std::vector<int> fresh_partition(const BlockGraph& graph, const std::vector<BlockWeight>& weights, int parts,
                                 double target, double accept);

}  // namespace suite::mpm2grid
