#include "solvers/mpm2grid/decomposition/diffuse_partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "core/errors.hpp"

namespace suite::mpm2grid {
namespace {

using Load = std::array<double, kQuantities>;

// What the moves work on: every block's part, the parts' loads, and which quantities count.
struct State {
  const BlockGraph& graph;
  const std::vector<BlockWeight>& weights;
  std::vector<int> part;
  std::vector<Load> load;
  Load mean{};
  Load limit{};   // the largest load over the mean to aim at, per quantity
  Load accept{};  // and to accept
  std::array<bool, kQuantities> balanced{};

  double weight(std::size_t b, std::size_t s) const { return static_cast<double>(weights[b][s]); }
  // The largest load over the mean, over the balanced quantities.
  double imbalance() const {
    double worst = 1;
    for (std::size_t s = 0; s < kQuantities; ++s)
      if (balanced[s])
        for (const Load& l : load) worst = std::max(worst, l[s] / mean[s]);
    return worst;
  }
  // Quantity s within its limit (or `bound`) on every part.
  bool within(std::size_t s, const Load& bound) const {
    for (const Load& l : load)
      if (l[s] > bound[s] * mean[s]) return false;
    return true;
  }
  // Every balanced quantity within its limit (or `bound`).
  bool within(const Load* bound = nullptr) const {
    for (std::size_t s = 0; s < kQuantities; ++s)
      if (balanced[s] && !within(s, bound ? *bound : limit)) return false;
    return true;
  }
  // Block b's neighbours in part p.
  int edges_to(std::size_t b, int p) const {
    int n = 0;
    for (int k = graph.start[b]; k < graph.start[b + 1]; ++k)
      n += part[static_cast<std::size_t>(graph.next[static_cast<std::size_t>(k)])] == p;
    return n;
  }
  void move(std::size_t b, int to) {
    for (std::size_t s = 0; s < kQuantities; ++s) {
      load[static_cast<std::size_t>(part[b])][s] -= weight(b, s);
      load[static_cast<std::size_t>(to)][s] += weight(b, s);
    }
    part[b] = to;
  }
};

// The potentials x of the part graph's Laplacian, L x = excess (the excesses sum to zero), by
// conjugate gradients with the degrees as preconditioner: x_p - x_q is the flow from p to q.
// Nothing when the parts' graph is not connected (some excess has no way to its deficit).
std::optional<std::vector<double>> potentials(const std::vector<std::vector<int>>& around,
                                              const std::vector<double>& excess) {
  const std::size_t P = around.size();
  // Connected: a walk from part 0 reaches every part.
  std::vector<char> seen(P, 0);
  std::vector<int> todo{0};
  seen[0] = 1;
  while (!todo.empty()) {
    const int p = todo.back();
    todo.pop_back();
    for (const int q : around[static_cast<std::size_t>(p)])
      if (!seen[static_cast<std::size_t>(q)]) seen[static_cast<std::size_t>(q)] = 1, todo.push_back(q);
  }
  if (std::count(seen.begin(), seen.end(), 0) > 0) return std::nullopt;
  const auto apply = [&](const std::vector<double>& v, std::vector<double>& out) {
    for (std::size_t p = 0; p < P; ++p) {
      double sum = static_cast<double>(around[p].size()) * v[p];
      for (const int q : around[p]) sum -= v[static_cast<std::size_t>(q)];
      out[p] = sum;
    }
  };
  std::vector<double> x(P, 0), r = excess, z(P), d(P), Ad(P);
  const auto precondition = [&] {
    for (std::size_t p = 0; p < P; ++p) z[p] = r[p] / static_cast<double>(around[p].size());
  };
  const auto dot = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (std::size_t p = 0; p < P; ++p) s += a[p] * b[p];
    return s;
  };
  const double stop = 1e-10 * std::sqrt(dot(excess, excess));
  precondition();
  d = z;
  double rz = dot(r, z);
  for (std::size_t it = 0; it < 10 * P + 100 && std::sqrt(dot(r, r)) > stop; ++it) {
    apply(d, Ad);
    const double curvature = dot(d, Ad);
    if (!(curvature > 0)) break;  // converged to round-off
    const double alpha = rz / curvature;
    for (std::size_t p = 0; p < P; ++p) x[p] += alpha * d[p], r[p] -= alpha * Ad[p];
    precondition();
    const double next = dot(r, z);
    for (std::size_t p = 0; p < P; ++p) d[p] = z[p] + next / rz * d[p];
    rz = next;
  }
  return x;
}

// One round: the flows that level the loads, then per pair of neighbouring parts the moves that
// carry them. The pairs go upstream first (by the larger potential of the two): a part passes
// on load after it has received what flows into it. False when the parts' graph is not
// connected.
bool diffusion_round(State& st, int parts) {
  const auto P = static_cast<std::size_t>(parts);
  const BlockGraph& g = st.graph;
  const std::size_t n = g.size();
  // Per quantity, the pairs of parts whose border can carry it: a block holding some on one
  // side, touching the other part (a border through soil alone carries no water).
  std::array<std::vector<std::vector<int>>, kQuantities> around;
  around.fill(std::vector<std::vector<int>>(P));
  std::vector<std::vector<int>> any(P);  // the pairs of parts that share a border
  // Per pair (p < q), the blocks on either side of their border (repeats allowed; blocks that
  // moved away are skipped where they are read).
  std::map<std::pair<int, int>, std::vector<std::size_t>> border;
  const auto on_border = [&](std::size_t b, int other) {
    auto& list = border[{std::min(st.part[b], other), std::max(st.part[b], other)}];
    if (list.empty() || list.back() != b) list.push_back(b);
  };
  for (std::size_t b = 0; b < n; ++b)
    for (int k = g.start[b]; k < g.start[b + 1]; ++k) {
      const int p = st.part[b], q = st.part[static_cast<std::size_t>(g.next[static_cast<std::size_t>(k)])];
      if (p == q) continue;
      on_border(b, q);
      any[static_cast<std::size_t>(p)].push_back(q), any[static_cast<std::size_t>(q)].push_back(p);
      for (std::size_t s = 0; s < kQuantities; ++s)
        if (st.weights[b][s] > 0)
          around[s][static_cast<std::size_t>(p)].push_back(q), around[s][static_cast<std::size_t>(q)].push_back(p);
    }
  for (auto* lists : {&any, &around[kSoil], &around[kWater], &around[kWetSoil]})
    for (auto& a : *lists) {
      std::sort(a.begin(), a.end());
      a.erase(std::unique(a.begin(), a.end()), a.end());
    }
  // Potentials in means of each quantity.
  std::array<std::vector<double>, kQuantities> x;
  x.fill(std::vector<double>(P, 0));
  for (std::size_t s = 0; s < kQuantities; ++s) {
    if (!st.balanced[s]) continue;
    std::vector<double> excess(P);
    for (std::size_t p = 0; p < P; ++p) excess[p] = (st.load[p][s] - st.mean[s]) / st.mean[s];
    auto potential = potentials(around[s], excess);
    // Some parts' borders do not carry the quantity to the others (the wet soil, which only
    // some borders cross): only a problem where it is out of balance (flows of zero keep it).
    if (!potential && !st.within(s, st.limit)) return false;
    if (potential) x[s] = std::move(*potential);
  }
  std::vector<std::tuple<double, int, int>> pairs;  // (-upstream potential, p, q), p < q
  for (std::size_t p = 0; p < P; ++p)
    for (const int q : any[p])
      if (static_cast<int>(p) < q) {
        double up = -1e300;
        for (std::size_t s = 0; s < kQuantities; ++s)
          if (st.balanced[s]) up = std::max({up, x[s][p], x[s][static_cast<std::size_t>(q)]});
        pairs.emplace_back(-up, static_cast<int>(p), q);
      }
  std::sort(pairs.begin(), pairs.end());
  // Per pair, the flow still to carry from p to q (in means): a move is taken when it brings
  // the flow nearer to zero; the one with the most neighbours on its new side (net of those it
  // leaves) first, then the largest reduction, then the lowest index. A block moves once a round.
  std::vector<char> moved(n, 0);
  const auto cost = [](const Load& f) {
    double c = 0;
    for (const double v : f) c += v * v;
    return c;
  };
  for (const auto& [up, p, q] : pairs) {
    Load flow{};
    for (std::size_t s = 0; s < kQuantities; ++s) {
      const auto& a = around[s][static_cast<std::size_t>(p)];
      if (st.balanced[s] && std::binary_search(a.begin(), a.end(), q))
        flow[s] = x[s][static_cast<std::size_t>(p)] - x[s][static_cast<std::size_t>(q)];
    }
    std::vector<std::size_t>& blocks = border[{p, q}];
    for (;;) {
      double best_cost = cost(flow);
      int best_gain = 0;
      std::size_t best = n;
      Load best_flow = flow;
      for (const std::size_t b : blocks) {
        const int from = st.part[b];
        if (moved[b] || (from != p && from != q)) continue;
        const int to = from == p ? q : p;
        const int next_to = st.edges_to(b, to);
        if (next_to == 0) continue;  // no longer on this border
        const int gain = next_to - st.edges_to(b, from);
        const double sign = from == p ? 1.0 : -1.0;
        Load f = flow;
        for (std::size_t s = 0; s < kQuantities; ++s)
          if (st.balanced[s]) f[s] -= sign * st.weight(b, s) / st.mean[s];
        const double c = cost(f);
        if (c >= cost(flow)) continue;
        if (best == n || gain > best_gain || (gain == best_gain && c < best_cost))
          best = b, best_gain = gain, best_cost = c, best_flow = f;
      }
      if (best == n) break;
      const int to = st.part[best] == p ? q : p;
      st.move(best, to);
      moved[best] = 1;
      flow = best_flow;
      // The block and its neighbours of other parts are on those borders now (the neighbours
      // it left behind among them).
      for (int k = g.start[best]; k < g.start[best + 1]; ++k) {
        const auto c = static_cast<std::size_t>(g.next[static_cast<std::size_t>(k)]);
        if (st.part[c] != to) on_border(c, to), on_border(best, st.part[c]);
      }
    }
  }
  return true;
}

// Border blocks go to the part holding most of their neighbours when that cuts fewer edges and
// keeps that part within its limit in every balanced quantity.
void refine_cut(State& st, int parts) {
  const BlockGraph& g = st.graph;
  std::vector<int> count(static_cast<std::size_t>(parts), 0);
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t b = 0; b < g.size(); ++b) {
      const int own = st.part[b];
      int best = own;
      for (int k = g.start[b]; k < g.start[b + 1]; ++k)
        ++count[static_cast<std::size_t>(st.part[static_cast<std::size_t>(g.next[static_cast<std::size_t>(k)])])];
      for (int k = g.start[b]; k < g.start[b + 1]; ++k) {
        const int q = st.part[static_cast<std::size_t>(g.next[static_cast<std::size_t>(k)])];
        const auto cq = count[static_cast<std::size_t>(q)], cb = count[static_cast<std::size_t>(best)];
        if (cq > cb || (cq == cb && q < best && best != own)) best = q;
      }
      const int gain = count[static_cast<std::size_t>(best)] - count[static_cast<std::size_t>(own)];
      for (int k = g.start[b]; k < g.start[b + 1]; ++k)
        count[static_cast<std::size_t>(st.part[static_cast<std::size_t>(g.next[static_cast<std::size_t>(k)])])] = 0;
      if (best == own || gain <= 0) continue;
      bool fits = true;
      for (std::size_t s = 0; s < kQuantities; ++s)
        if (st.balanced[s] && st.weight(b, s) > 0)
          fits = fits && st.load[static_cast<std::size_t>(best)][s] + st.weight(b, s) <= st.limit[s] * st.mean[s];
      if (fits) st.move(b, best);
    }
}

}  // namespace

std::optional<Diffused> diffuse_partition(const BlockGraph& graph, const std::vector<BlockWeight>& weights,
                                          const std::vector<int>& previous, int parts, double target, double accept) {
  const std::size_t n = graph.size();
  if (weights.size() != n || previous.size() != n)
    throw LibraryError("diffuse_partition: one weight pair and one previous part per block expected");
  for (const int p : previous)
    if (p < -1 || p >= parts) throw LibraryError(fmt::format("diffuse_partition: part {} of {} parts", p, parts));
  const auto P = static_cast<std::size_t>(parts);
  State st{graph, weights, previous, std::vector<Load>(P, Load{})};
  if (parts <= 1) return Diffused{std::vector<int>(n, 0), 1, 0};
  // Blocks without a part join the part most of their neighbours are in, repeatedly (a
  // block reached only through such blocks waits for them); any left (no block around has a
  // part) go to part 0, whose load the rounds then spread.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t b = 0; b < n; ++b) {
      if (st.part[b] >= 0) continue;
      std::map<int, int> around;
      for (int k = graph.start[b]; k < graph.start[b + 1]; ++k)
        if (const int q = st.part[static_cast<std::size_t>(graph.next[static_cast<std::size_t>(k)])]; q >= 0)
          ++around[q];
      if (around.empty()) continue;
      st.part[b] = std::max_element(around.begin(), around.end(), [](const auto& a, const auto& c) {
                     return a.second < c.second;
                   })->first;
      changed = true;
    }
  }
  for (int& p : st.part)
    if (p < 0) p = 0;
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t s = 0; s < kQuantities; ++s) st.load[static_cast<std::size_t>(st.part[b])][s] += st.weight(b, s);
  for (std::size_t s = 0; s < kQuantities; ++s) {
    double total = 0;
    for (const Load& l : st.load) total += l[s];
    st.mean[s] = total / static_cast<double>(parts);
    st.balanced[s] = total >= 64.0 * parts;
    // Blocks move whole: half the largest block above the mean where that is more than the target
    // (or the quantity's tolerance, partition.hpp).
    double block = 0;
    for (std::size_t b = 0; b < n; ++b) block = std::max(block, st.weight(b, s));
    st.limit[s] = st.balanced[s] ? std::max({target, kTolerance[s], 1 + block / (2 * st.mean[s])}) : 0;
    st.accept[s] = std::max(st.limit[s], accept);
  }
  // Rounds until balanced: each carries most of the flow; the blocks' sizes leave a remainder.
  // A partition already within the target is left as it is.
  const bool within = st.within();
  for (int round = 0; round < 8 && !st.within(); ++round)
    if (!diffusion_round(st, parts)) return std::nullopt;
  if (!within) refine_cut(st, parts);
  if (!st.within(&st.accept)) return std::nullopt;
  Diffused out{std::move(st.part), st.imbalance(), 0};
  for (std::size_t b = 0; b < n; ++b) out.moved += previous[b] >= 0 && previous[b] != out.part[b];
  return out;
}

namespace {

// Every quantity with at least 64 particles a part within its tolerance (partition.hpp) of its
// mean, plus its largest block (blocks are whole), on every part: what METIS promises.
bool within_tolerance(const std::vector<BlockWeight>& weights, const std::vector<int>& part, int parts) {
  std::vector<BlockWeight> load(static_cast<std::size_t>(parts), BlockWeight{});
  BlockWeight total{}, block{};
  for (std::size_t b = 0; b < weights.size(); ++b)
    for (std::size_t q = 0; q < kQuantities; ++q) {
      load[static_cast<std::size_t>(part[b])][q] += weights[b][q];
      total[q] += weights[b][q];
      block[q] = std::max(block[q], weights[b][q]);
    }
  for (std::size_t q = 0; q < kQuantities; ++q) {
    if (total[q] < 64LL * parts) continue;
    const double mean = static_cast<double>(total[q]) / parts;
    for (const BlockWeight& l : load)
      if (static_cast<double>(l[q]) > kTolerance[q] * mean + static_cast<double>(block[q])) return false;
  }
  return true;
}

}  // namespace

std::vector<int> fresh_partition(const BlockGraph& graph, const std::vector<BlockWeight>& weights, int parts,
                                 double target, double accept) {
  if (std::none_of(weights.begin(), weights.end(), [](const BlockWeight& w) { return w[kWetSoil] > 0; }))
    return partition_blocks(graph, weights, parts);
  for (const bool bisection : {false, true}) {
    std::vector<int> part = partition_blocks(graph, weights, parts, bisection);
    if (within_tolerance(weights, part, parts)) return part;
    if (auto diffused = diffuse_partition(graph, weights, part, parts, target, accept))
      return std::move(diffused->part);
  }
  std::vector<BlockWeight> dry = weights;
  for (BlockWeight& w : dry) w[kWetSoil] = 0;
  return partition_blocks(graph, dry, parts);
}

}  // namespace suite::mpm2grid
