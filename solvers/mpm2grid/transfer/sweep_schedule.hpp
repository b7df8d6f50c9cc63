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
#include <array>
#include <cstddef>
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

// A block's colour: the parities of its coordinates (0 .. 2^Dim - 1).
template <int Dim>
std::size_t block_colour(const Index<Dim>& b) {
  int c = 0;
  for (int d = 0; d < Dim; ++d) c |= (b[d] & 1) << d;
  return static_cast<std::size_t>(c);
}

// rank[b]: the place of block b's group when the groups go colour by colour (the parities of the
// block coordinates), in index order within a colour: the order P2G's schedule sweeps them.
// Particles put in this order (group_order's rank) read each part of a colour as one stretch of
// memory; in block order a part's groups lie 2^Dim groups apart among the particles, and one
// thread's P2G took a quarter longer when it swept them so.
template <int Dim>
void colour_ranks(const BlockGrid<Dim>& grid, std::vector<int>& rank) {
  constexpr int kColours = 1 << Dim;
  const auto colour = [&](std::size_t b) { return block_colour<Dim>(grid.block_coord(b)); };
  std::array<int, kColours + 1> next{};
  for (std::size_t b = 0; b < grid.blocks(); ++b) ++next[colour(b) + 1];
  for (int c = 0; c < kColours; ++c) next[static_cast<std::size_t>(c) + 1] += next[static_cast<std::size_t>(c)];
  rank.resize(grid.blocks());
  for (std::size_t b = 0; b < grid.blocks(); ++b) rank[b] = next[colour(b)]++;
}

// P2G's parts by colour for one species, built from the particles' groups (the indices of the
// blocks holding their stencils' first nodes, as touch_blocks finds them when the grid is built)
// once per subset of the particles, and kept while the particles and the blocks stay as they were
// (reset() when the grid is built again). The implicit forces spread each species many times a
// step (once per residual): the parts are cut once.
template <int Dim>
class ColourSchedule {
 public:
  static constexpr int kColours = 1 << Dim;

  // The particles' groups, in the particles' order; filled by the grid's build, which calls reset().
  std::vector<int>& groups() { return groups_; }
  void reset() {
    for (auto& cut : cuts_) cut.built = false;
  }

  // colours[c]: the parts of colour c, each a whole number of groups of about kPart particles or
  // more, the groups in the order of their block indices, a group's runs in the particles' order.
  // `threads` find the runs. A subset's parts are kept for its flags and value (the flags' values
  // must not change until reset()).
  const std::vector<SweepParts>& colours(const BlockGrid<Dim>& grid, const ParticleSubset& subset, int threads) {
    Cut& cut = cuts_[subset.flags ? (subset.value ? 1 : 0) : 2];
    if (!cut.built || cut.flags != subset.flags) build(grid, subset, threads, cut.colours);
    cut.built = true, cut.flags = subset.flags;
    return cut.colours;
  }

 private:
  struct GroupRun {
    int group;
    ParticleRun run;
  };
  struct Cut {
    bool built = false;
    const std::vector<char>* flags = nullptr;
    std::vector<SweepParts> colours;
  };

  void build(const BlockGrid<Dim>& grid, const ParticleSubset& subset, int threads, std::vector<SweepParts>& colours) {
    // The runs: consecutive particles of one group (those outside the subset between them skipped),
    // found in parts of kPart particles, then joined across the parts' ends.
    const std::size_t n = groups_.size(), pieces = (n + kPart - 1) / kPart;
    found_.resize(pieces);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t k = 0; k < pieces; ++k) {
      auto& out = found_[k];
      out.clear();
      for (std::size_t p = k * kPart; p < std::min(n, (k + 1) * kPart); ++p) {
        if (!subset.has(p)) continue;
        if (out.empty() || out.back().group != groups_[p]) out.push_back({groups_[p], {p, p + 1}});
        out.back().run.end = p + 1;
      }
    }
    runs_.clear();
    for (const auto& piece : found_)
      for (const GroupRun& r : piece)
        if (!runs_.empty() && runs_.back().group == r.group)
          runs_.back().run.end = r.run.end;
        else
          runs_.push_back(r);
    // The runs by group (a counting sort, keeping each group's runs in order), the groups in the
    // order of their indices, each to its colour: the parities of its block coordinates. Groups of
    // one colour touch disjoint blocks (their 2^Dim blocks g + {0, 1}^Dim), so the sums each node
    // receives do not depend on the groups' order within a colour.
    first_.assign(grid.blocks() + 1, 0);
    for (const GroupRun& r : runs_) ++first_[static_cast<std::size_t>(r.group) + 1];
    for (std::size_t b = 0; b < grid.blocks(); ++b) first_[b + 1] += first_[b];
    by_group_.resize(runs_.size());
    for (const GroupRun& r : runs_) by_group_[first_[static_cast<std::size_t>(r.group)]++] = r.run;
    colours.resize(kColours);
    for (auto& c : colours) c.clear();
    std::array<std::size_t, kColours> in_part{};
    for (std::size_t b = 0, r = 0; b < grid.blocks(); ++b) {
      if (r == first_[b]) continue;  // no runs in group b
      const std::size_t colour = block_colour<Dim>(grid.block_coord(b));
      SweepParts& parts = colours[colour];
      std::size_t& filled = in_part[colour];
      for (; r < first_[b]; ++r) {
        parts.add_run(by_group_[r]);
        filled += by_group_[r].end - by_group_[r].begin;
      }
      if (filled >= kPart) parts.end_part(), filled = 0;
    }
    for (auto& c : colours) c.end_part();
  }

  std::vector<int> groups_;
  std::array<Cut, 3> cuts_;  // for the subsets of value 0 and 1, and for all the particles
  // Scratch: each piece's runs, the joined runs, the runs' start per group and the runs by group.
  std::vector<std::vector<GroupRun>> found_;
  std::vector<GroupRun> runs_;
  std::vector<std::size_t> first_;
  std::vector<ParticleRun> by_group_;
};

}  // namespace suite::mpm2grid
