#pragma once
// The partition of the active grid blocks over the ranks (docs/methods/mpm2grid.md, "Decomposition and
// performance design"): METIS k-way on the blocks' adjacency graph (blocks sharing a face, an
// edge or a corner: a particle's stencil spans up to 2^Dim of them), with one balance
// constraint per quantity of work (BlockWeight: a block's soil and water particle counts, and
// optionally with the consistent drag its wet soil), so that each rank gets its share of the
// soil's return mapping, the water's cheaper update and the drag's matrix rows. Cutting few
// graph edges keeps few blocks on the ranks' borders, which is what the halo traffic scales with.
// keep_ranks() then renames the parts so that as much of the work as possible stays on the rank
// that had it: a rebalance moves only the particles it must.
#include <array>
#include <vector>

#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

// The work a block is home to, per quantity: its soil and water particles, and its wet soil,
// the soil particles of a block that is also home to water particles (where the consistent
// drag's coupled nodes and their matrix rows are; 0 where it is not balanced,
// decomposition.balance_wet_soil). A proxy at the blocks' scale: a coupled node also lies in a
// block of one species next to a block of the other.
// Each is balanced over the ranks on its own: the step's phases wait for each other in the halo
// exchanges, so a rank's share of each phase's work counts, not of their sum.
enum Quantity : std::size_t { kSoil = 0, kWater = 1, kWetSoil = 2 };
constexpr std::size_t kQuantities = 3;
using BlockWeight = std::array<long long, kQuantities>;
// Wet soil from a block's soil and water particles.
inline long long wet_soil(long long soil, long long water) {
  return soil > 0 && water > 0 ? soil : 0;
}
// How far above its mean a part's share of each quantity may come: METIS's tolerance (ubvec),
// and the diffusion's least target. 1% for the particles (a rank's share above the mean is
// time every other rank waits in the halo exchanges; METIS's default 5% left example 2 nearly
// that far out of balance: docs/mpm2grid.md, "Over several ranks"; blocks of 16 to 64
// particles leave METIS room to meet 1%). 10% for the wet soil: a thin layer where the water
// meets the soil (example 2 at h = 0.025 m: 1,862 particles, 116 a rank on 16 ranks, 61 in
// the largest block); asked for 1% there too, METIS left the particles 8% above their mean.
constexpr std::array<double, kQuantities> kTolerance{1.01, 1.01, 1.10};

// The blocks' adjacency in compressed rows: block i's neighbours (the 3^Dim - 1 around it that
// are in the list) are next[start[i] .. start[i + 1]), in increasing offset order.
struct BlockGraph {
  std::vector<int> start{0}, next;
  std::size_t size() const { return start.size() - 1; }
};
template <int Dim>
BlockGraph block_graph(const std::vector<Index<Dim>>& blocks);

// The part (0 .. parts - 1) of every block; weights[i] is block i's work. A quantity that is
// zero everywhere is no constraint; blocks without particles weigh nothing
// but still join their neighbours' parts through the graph. Deterministic: the same input gives
// the same parts on every rank. Throws LibraryError when METIS fails.
// `bisection`: METIS's recursive bisection in place of its k-way partition (which cuts fewer
// edges, but with several constraints can leave one well above its tolerance).
std::vector<int> partition_blocks(const BlockGraph& graph, const std::vector<BlockWeight>& weights, int parts,
                                  bool bisection = false);

// Renames the parts: previous[i] is block i's rank before (-1: none), weight[i] its work. Pairs
// of (new part, old rank) are matched greedily by the work they share, largest first; parts
// left over get the ranks left over in increasing order.
std::vector<int> keep_ranks(const std::vector<int>& parts, const std::vector<int>& previous,
                            const std::vector<long long>& weight, int ranks);

}  // namespace suite::mpm2grid
