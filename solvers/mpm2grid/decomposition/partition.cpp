#include "solvers/mpm2grid/decomposition/partition.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
#include <tuple>
#include <unordered_map>

#include "core/errors.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

template <int Dim>
BlockGraph block_graph(const std::vector<Index<Dim>>& blocks) {
  using Grid = BlockGrid<Dim>;
  const std::size_t n = blocks.size();
  std::unordered_map<typename Grid::Key, int> index;
  index.reserve(n);
  for (std::size_t i = 0; i < n; ++i) index.emplace(Grid::key(blocks[i]), static_cast<int>(i));
  int around = 1;
  for (int d = 0; d < Dim; ++d) around *= 3;
  BlockGraph g;
  g.start.reserve(n + 1);
  g.next.reserve(n * static_cast<std::size_t>(around - 1));
  for (std::size_t i = 0; i < n; ++i) {
    for (int o = 0; o < around; ++o) {
      Index<Dim> b = blocks[i];
      int r = o, centre = 1;
      for (int d = 0; d < Dim; ++d) {
        const int step = r % 3 - 1;
        b[d] += step;
        centre &= step == 0;
        r /= 3;
      }
      if (centre) continue;
      const auto it = index.find(Grid::key(b));
      if (it != index.end()) g.next.push_back(it->second);
    }
    g.start.push_back(static_cast<int>(g.next.size()));
  }
  return g;
}

std::vector<int> partition_blocks(const BlockGraph& graph, const std::vector<BlockWeight>& weights, int parts,
                                  bool bisection) {
  const std::size_t n = graph.size();
  if (weights.size() != n) throw LibraryError("partition_blocks: one weight per block expected");
  std::vector<int> part(n, 0);
  if (parts <= 1 || n == 0) return part;
  if (n <= static_cast<std::size_t>(parts)) {
    for (std::size_t i = 0; i < n; ++i) part[i] = static_cast<int>(i);
    return part;
  }
  std::vector<idx_t> xadj(graph.start.begin(), graph.start.end()), adjncy(graph.next.begin(), graph.next.end());
  // The constraints: the quantities present anywhere (one weight of 1 per block if none is).
  BlockWeight total{};
  for (const auto& w : weights)
    for (std::size_t q = 0; q < kQuantities; ++q) total[q] += w[q];
  std::vector<std::size_t> present;
  for (std::size_t q = 0; q < kQuantities; ++q)
    if (total[q] > 0) present.push_back(q);
  idx_t ncon = std::max<idx_t>(1, static_cast<idx_t>(present.size()));
  std::vector<idx_t> vwgt(n * static_cast<std::size_t>(ncon), 1);
  if (!present.empty())
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < present.size(); ++c)
        vwgt[i * present.size() + c] = static_cast<idx_t>(weights[i][present[c]]);
  std::vector<real_t> ubvec(static_cast<std::size_t>(ncon), static_cast<real_t>(kTolerance[kSoil]));
  for (std::size_t c = 0; c < present.size(); ++c) ubvec[c] = static_cast<real_t>(kTolerance[present[c]]);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  idx_t nvtxs = static_cast<idx_t>(n), nparts = parts, objval = 0;
  std::vector<idx_t> result(n, 0);
  const auto metis = bisection ? METIS_PartGraphRecursive : METIS_PartGraphKway;
  const int status = metis(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr, &nparts, nullptr,
                           ubvec.data(), options, &objval, result.data());
  if (status != METIS_OK)
    throw LibraryError(fmt::format("METIS_PartGraph{} failed (status {}) on {} blocks for {} ranks",
                                   bisection ? "Recursive" : "Kway", status, n, parts));
  for (std::size_t i = 0; i < n; ++i) part[i] = static_cast<int>(result[i]);
  return part;
}

std::vector<int> keep_ranks(const std::vector<int>& parts, const std::vector<int>& previous,
                            const std::vector<long long>& weight, int ranks) {
  const auto R = static_cast<std::size_t>(ranks);
  std::vector<long long> shared(R * R, 0);  // [new part][old rank]
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (previous[i] >= 0)
      shared[static_cast<std::size_t>(parts[i]) * R + static_cast<std::size_t>(previous[i])] += weight[i] + 1;
  std::vector<std::tuple<long long, int, int>> pairs;  // (-shared work, part, rank): largest first, ties by index
  for (std::size_t p = 0; p < R; ++p)
    for (std::size_t r = 0; r < R; ++r)
      if (shared[p * R + r] > 0) pairs.emplace_back(-shared[p * R + r], static_cast<int>(p), static_cast<int>(r));
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> rank_of(R, -1);
  std::vector<char> taken(R, 0);
  for (const auto& [w, p, r] : pairs)
    if (rank_of[static_cast<std::size_t>(p)] < 0 && !taken[static_cast<std::size_t>(r)])
      rank_of[static_cast<std::size_t>(p)] = r, taken[static_cast<std::size_t>(r)] = 1;
  std::size_t next = 0;
  for (std::size_t p = 0; p < R; ++p) {
    if (rank_of[p] >= 0) continue;
    while (taken[next]) ++next;
    rank_of[p] = static_cast<int>(next);
    taken[next] = 1;
  }
  std::vector<int> out(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) out[i] = rank_of[static_cast<std::size_t>(parts[i])];
  return out;
}

template BlockGraph block_graph<2>(const std::vector<Index<2>>&);
template BlockGraph block_graph<3>(const std::vector<Index<3>>&);

}  // namespace suite::mpm2grid
