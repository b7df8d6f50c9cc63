#pragma once
// The partition of the active grid blocks over the ranks (docs/methods/mpm2grid.md, "Decomposition and
// performance design"): METIS k-way on the blocks' adjacency graph (blocks sharing a face, an
// edge or a corner: a particle's stencil spans up to 2^Dim of them), with one balance
// constraint per species (a block's soil and water particle counts), so that each rank gets
// its share of both the soil's return mapping and the water's cheaper update. Cutting few
// graph edges keeps few blocks on the ranks' borders, which is what the halo traffic scales with.
// keep_ranks() then renames the parts so that as much of the work as possible stays on the rank
// that had it: a rebalance moves only the particles it must.
#include <array>
#include <vector>

#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

// The blocks' adjacency in compressed rows: block i's neighbours (the 3^Dim - 1 around it that
// are in the list) are next[start[i] .. start[i + 1]), in increasing offset order.
struct BlockGraph {
  std::vector<int> start{0}, next;
  std::size_t size() const { return start.size() - 1; }
};
template <int Dim>
BlockGraph block_graph(const std::vector<Index<Dim>>& blocks);

// The part (0 .. parts - 1) of every block. weights[i] = {soil, water} particles in block i.
// A species with no particle anywhere is no constraint; blocks without particles weigh nothing
// but still join their neighbours' parts through the graph. Deterministic: the same input gives
// the same parts on every rank. Throws LibraryError when METIS fails.
std::vector<int> partition_blocks(const BlockGraph& graph, const std::vector<std::array<long long, 2>>& weights,
                                  int parts);

// Renames the parts: previous[i] is block i's rank before (-1: none), weight[i] its work. Pairs
// of (new part, old rank) are matched greedily by the work they share, largest first; parts
// left over get the ranks left over in increasing order.
std::vector<int> keep_ranks(const std::vector<int>& parts, const std::vector<int>& previous,
                            const std::vector<long long>& weight, int ranks);

}  // namespace suite::mpm2grid
