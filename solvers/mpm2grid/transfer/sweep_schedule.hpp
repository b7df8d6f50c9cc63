#pragma once
// Threads inside a rank (docs/methods/mpm2grid.md, "Threads inside a rank"): how the transfers'
// sweeps (transfer/stencil_rows.hpp, sweep_groups) share one species' particles among OpenMP
// threads, each with its own node tile.
//
// G2P writes only to its particles: any cut works, and the threads take parts of kPart particles
// as they come free (a slow core takes fewer). Each particle's values are the same as one thread's.
// P2G adds each group's tile to the nodes of the 2^Dim blocks g + {0, 1}^Dim. Groups whose block
// coordinates have the same parities (a colour: 4 in 2D, 8 in 3D) touch disjoint blocks, so the
// threads add the groups of one colour at once and the colours one after the other. A group's
// runs of particles stay together, in their order, in one part. Each node then receives its sums
// in an order fixed by the particles alone (colour by colour, run by run), whatever the number of
// threads: runs on 2 or 16 threads are bit for bit the same. (One thread sweeps the particles in
// their order instead, as before threads came: the two orders differ at round-off.)
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

// The parts of one sweep, each a list of runs one thread takes in order.
class SweepParts {
 public:
  std::size_t size() const { return starts_.empty() ? 0 : starts_.size() - 1; }
  std::span<const ParticleRun> operator[](std::size_t k) const {
    return std::span<const ParticleRun>(runs_).subspan(starts_[k], starts_[k + 1] - starts_[k]);
  }
  void clear() { runs_.clear(), starts_.assign(1, 0); }
  void add_run(const ParticleRun& r) { runs_.push_back(r); }
  void end_part() {
    if (runs_.size() > starts_.back()) starts_.push_back(runs_.size());
  }

 private:
  std::vector<ParticleRun> runs_;
  std::vector<std::size_t> starts_{0};
};

// Particles per part: a part's work (microseconds) dwarfs taking it, and a species has tens of
// parts per thread to even out slow cores.
inline constexpr std::size_t kPart = 2048;

// G2P's parts: kPart consecutive particles each.
inline void cut_evenly(std::size_t particles, SweepParts& parts) {
  parts.clear();
  for (std::size_t b = 0; b < particles; b += kPart) {
    parts.add_run({b, std::min(particles, b + kPart)});
    parts.end_part();
  }
}

// P2G's parts by colour: colours[c] the parts of colour c, each a whole number of groups of about
// kPart particles or more. `keys` is scratch space; `threads` find the particles' groups.
template <int Dim>
void cut_by_colour(const std::vector<Vec<Dim>>& x, double h, const ParticleSubset& subset, int threads,
                   std::vector<SweepParts>& colours, std::vector<std::uint64_t>& keys) {
  using Grid = BlockGrid<Dim>;
  constexpr int kColours = 1 << Dim;
  constexpr std::uint64_t kNone = ~std::uint64_t{0};
  const std::size_t n = x.size();
  keys.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t p = 0; p < n; ++p)
    keys[p] = subset.has(p) ? Grid::key(Grid::block_holding(stencil_base(x[p], h))) : kNone;
  // The runs: consecutive particles of one group (those outside the subset between them skipped).
  struct Run {
    std::uint64_t key;
    int colour;
    ParticleRun run;
  };
  std::vector<Run> runs;
  std::uint64_t current = kNone;
  for (std::size_t p = 0; p < n; ++p) {
    if (keys[p] == kNone) continue;
    if (keys[p] != current) {
      current = keys[p];
      const Index<Dim> g = Grid::unkey(current);
      int colour = 0;
      for (int d = 0; d < Dim; ++d) colour |= (g[d] & 1) << d;
      runs.push_back({current, colour, {p, p + 1}});
    }
    runs.back().run.end = p + 1;
  }
  // Colour, then group, then the particles' order.
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) {
    if (a.colour != b.colour) return a.colour < b.colour;
    if (a.key != b.key) return a.key < b.key;
    return a.run.begin < b.run.begin;
  });
  colours.resize(kColours);
  for (auto& c : colours) c.clear();
  std::size_t in_part = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    SweepParts& parts = colours[static_cast<std::size_t>(runs[r].colour)];
    parts.add_run(runs[r].run);
    in_part += runs[r].run.end - runs[r].run.begin;
    const bool group_ends = r + 1 == runs.size() || runs[r + 1].key != runs[r].key;
    const bool colour_ends = r + 1 == runs.size() || runs[r + 1].colour != runs[r].colour;
    if (colour_ends || (group_ends && in_part >= kPart)) parts.end_part(), in_part = 0;
  }
}

}  // namespace suite::mpm2grid
