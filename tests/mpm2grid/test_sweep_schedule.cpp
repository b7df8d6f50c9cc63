// Threads inside a rank (transfer/sweep_schedule.hpp, transfer/particle_order.hpp,
// grid/block_grid.hpp, model/blow_up.hpp): the threaded versions of the grid's build, the
// particle order, P2G's schedule and the blow-up scan give what one thread gives, and P2G's
// colour schedule covers each particle once, in groups of one colour that touch disjoint blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/model/blow_up.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"
#include "solvers/mpm2grid/transfer/particle_order.hpp"
#include "solvers/mpm2grid/transfer/sweep_schedule.hpp"

namespace suite::mpm2grid {
namespace {

// n particles scattered over a box of 6 x 3 m (2D) or 2 m per axis (3D), in random order (many
// runs per group), velocity 1 m/s along x, 2 kg each.
template <int Dim>
Particles<Dim> scattered(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles<Dim> P;
  for (std::size_t i = 0; i < n; ++i) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = (Dim == 2 ? (d == 0 ? 6.0 : 3.0) : 2.0) * u(rng);
    P.add(x, Vec<Dim>::UnitX(), 2.0, 0.01);
  }
  return P;
}

// A block index array over a box gives every block the index the hash table alone gives, inside
// the box and out, and forgets its blocks at clear().
TEST(BlockGrid, DenseBoxIndexesAsTheHashTable) {
  const double h = 0.05;
  const auto P = scattered<2>(20000, 1);
  BlockGrid<2> hashed(h), boxed(h);
  // A box over part of the particles' blocks: the rest go to the hash table.
  ASSERT_TRUE(boxed.set_dense_box({5, 2}, {20, 9}));
  std::vector<int> groups_hashed, groups_boxed;
  for (int round = 0; round < 2; ++round) {  // the second after clear()
    hashed.clear(), boxed.clear();
    touch_blocks(P, hashed, &groups_hashed);
    touch_blocks(P, boxed, &groups_boxed);
    ASSERT_EQ(hashed.blocks(), boxed.blocks());
    EXPECT_EQ(groups_hashed, groups_boxed);
    std::size_t inside = 0;
    for (std::size_t b = 0; b < hashed.blocks(); ++b) {
      const Index<2>& c = hashed.block_coord(b);
      EXPECT_EQ(boxed.block_coord(b), c);
      EXPECT_EQ(boxed.find_block(c), static_cast<int>(b));
      inside += c[0] >= 5 && c[0] <= 20 && c[1] >= 2 && c[1] <= 9;
    }
    EXPECT_GT(inside, 0u);
    EXPECT_LT(inside, hashed.blocks());
    // Nodes: one inside the box, one outside.
    for (const Index<2> node : {Index<2>{30, 15}, Index<2>{100, 50}})
      EXPECT_EQ(boxed.slot_of(node), hashed.slot_of(node));
  }
  boxed.clear();
  EXPECT_EQ(boxed.find_block({10, 5}), -1);
  EXPECT_EQ(boxed.activate({10, 5}), 0);
  EXPECT_EQ(boxed.find_block({10, 5}), 0);
  EXPECT_THROW(boxed.set_dense_box({0, 0}, {10, 10}), std::logic_error);  // blocks are active
}

TEST(BlockGrid, DenseBoxRefusesTooManyBlocks) {
  BlockGrid<3> grid(0.01);
  EXPECT_FALSE(grid.set_dense_box({0, 0, 0}, {2000, 2000, 2000}));
  EXPECT_EQ(grid.activate({5, 5, 5}), 0);  // the hash table alone
  EXPECT_EQ(grid.find_block({5, 5, 5}), 0);
}

// Counting runs and groups and copying the arrays over threads changes nothing.
TEST(ParticleOrder, ThreadsGiveTheSameOrder) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, 499);
  std::vector<int> scattered_groups(50000);
  for (int& g : scattered_groups) g = pick(rng);
  const auto order = group_order(scattered_groups, 500);
  ASSERT_FALSE(order.empty());
  EXPECT_EQ(group_order(scattered_groups, 500, 3), order);
  std::vector<int> one = scattered_groups, three = scattered_groups;
  apply_order(one, order);
  apply_order(three, order, 3);
  EXPECT_EQ(one, three);
  EXPECT_TRUE(std::is_sorted(one.begin(), one.end()));
  EXPECT_TRUE(group_order(one, 500, 3).empty());
}

// With the colour ranks, group_order puts the particles colour by colour, each colour's groups in
// block order, each group's particles in their order: every part of the schedule is then one
// stretch of particles.
TEST(ColourSchedule, ColourOrderMakesEachPartOneStretch) {
  auto P = scattered<2>(30000, 17);
  BlockGrid<2> grid(0.05);
  std::vector<int> groups, rank;
  touch_blocks(P, grid, &groups);
  colour_ranks(grid, rank);
  std::vector<int> sorted_rank = rank;
  std::sort(sorted_rank.begin(), sorted_rank.end());
  for (std::size_t b = 0; b < rank.size(); ++b) ASSERT_EQ(sorted_rank[b], static_cast<int>(b));  // a permutation
  const auto order = group_order(groups, grid.blocks(), 2, &rank);
  ASSERT_FALSE(order.empty());
  EXPECT_EQ(group_order(groups, grid.blocks(), 1, &rank), order);
  P.for_each_array([&](auto& values) { apply_order(values, order); });
  apply_order(groups, order);
  for (std::size_t p = 1; p < P.size(); ++p) {
    ASSERT_LE(rank[static_cast<std::size_t>(groups[p - 1])], rank[static_cast<std::size_t>(groups[p])]);
    if (groups[p - 1] == groups[p]) {
      ASSERT_LT(P.id[p - 1], P.id[p]);  // a group's particles in their order
    }
  }
  ColourSchedule<2> schedule;
  schedule.groups() = groups;
  std::size_t next = 0;
  for (const SweepParts& parts : schedule.colours(grid, {}, 2))
    for (std::size_t k = 0; k < parts.size(); ++k)
      for (const ParticleRun& r : parts[k]) {
        EXPECT_EQ(r.begin, next) << "a part's runs follow each other";
        next = r.end;
      }
  EXPECT_EQ(next, P.size());
}

// P2G's schedule: each particle of the subset in exactly one run; a run's particles of one group;
// a group's runs in one part, in the particles' order; the parts of one colour add to disjoint
// blocks; the same parts for any number of threads.
template <int Dim>
void check_schedule(const Particles<Dim>& P, const ParticleSubset& subset) {
  const double h = 0.05;
  BlockGrid<Dim> grid(h);
  ColourSchedule<Dim> one, three;
  touch_blocks(P, grid, &one.groups());
  three.groups() = one.groups();
  const auto& colours = one.colours(grid, subset, 1);
  const auto& colours3 = three.colours(grid, subset, 3);
  ASSERT_EQ(colours.size(), std::size_t{1} << Dim);
  std::vector<int> seen(P.size(), 0);
  std::map<int, std::pair<std::size_t, std::size_t>> part_of_group;  // group -> (colour, part)
  for (std::size_t c = 0; c < colours.size(); ++c) {
    ASSERT_EQ(colours[c].size(), colours3[c].size());
    std::map<Index<Dim>, std::size_t> part_of_block;
    for (std::size_t k = 0; k < colours[c].size(); ++k) {
      const auto runs = colours[c][k], runs3 = colours3[c][k];
      ASSERT_EQ(runs.size(), runs3.size());
      std::size_t last_end = 0;
      int last_group = -1;
      for (std::size_t r = 0; r < runs.size(); ++r) {
        EXPECT_EQ(runs[r].begin, runs3[r].begin);
        EXPECT_EQ(runs[r].end, runs3[r].end);
        const int g = one.groups()[runs[r].begin];
        // The blocks the group's tile adds to: no other part of the colour adds to them.
        const Index<Dim>& b = grid.block_coord(static_cast<std::size_t>(g));
        for (int corner = 0; corner < (1 << Dim); ++corner) {
          Index<Dim> touched = b;
          for (int d = 0; d < Dim; ++d) touched[d] += (corner >> d) & 1;
          const auto [at, added] = part_of_block.try_emplace(touched, k);
          EXPECT_TRUE(added || at->second == k)
              << "colour " << c << ": a block in parts " << at->second << " and " << k;
        }
        const auto [it, fresh] = part_of_group.try_emplace(g, c, k);
        EXPECT_TRUE(fresh || (it->second == std::pair{c, k} && g == last_group)) << "group " << g << " split";
        if (g == last_group) {
          EXPECT_GE(runs[r].begin, last_end);
        }
        for (std::size_t p = runs[r].begin; p < runs[r].end; ++p)
          if (subset.has(p)) {
            EXPECT_EQ(one.groups()[p], g);
            ++seen[p];
          }
        last_group = g, last_end = runs[r].end;
      }
    }
  }
  for (std::size_t p = 0; p < P.size(); ++p) EXPECT_EQ(seen[p], subset.has(p) ? 1 : 0) << "particle " << p;
}

TEST(ColourSchedule, CoversEachParticleOnceByColour2D) {
  const auto P = scattered<2>(30000, 5);
  check_schedule(P, {});
  std::vector<char> free(P.size());
  for (std::size_t p = 0; p < P.size(); ++p) free[p] = P.x[p][1] > 1.0;
  check_schedule(P, {&free, 1});
  check_schedule(P, {&free, 0});
}

TEST(ColourSchedule, CoversEachParticleOnceByColour3D) {
  check_schedule(scattered<3>(30000, 7), {});
}

// Two clusters 2 km apart (blocks far outside any box the others span).
TEST(ColourSchedule, CoversEachParticleOnceWithFarApartParticles) {
  auto P = scattered<2>(20000, 13);
  for (std::size_t p = 0; p < P.size(); p += 2) P.x[p][0] += 2000.0;
  check_schedule(P, {});
}

// The schedule's sweep, colour by colour, adds the same node sums as one sweep in the particles'
// order (to round-off: only the order of each node's sums changes).
TEST(ColourSchedule, SpreadsWhatOneSweepSpreads) {
  const auto P = scattered<2>(20000, 9);
  BlockGrid<2> grid(0.05);
  ColourSchedule<2> schedule;
  touch_blocks(P, grid, &schedule.groups());
  NodeFields<2> whole, by_colour;
  whole.reset(grid.nodes()), by_colour.reset(grid.nodes());
  const P2GSources<2> in{.gravity = Vec<2>(0, -9.81)};
  particles_to_grid(P, in, grid, whole);
  for (const SweepParts& parts : schedule.colours(grid, {}, 2))
    for (std::size_t k = 0; k < parts.size(); ++k) {
      P2GSources<2> part = in;
      part.runs = parts[k];
      particles_to_grid(P, part, grid, by_colour);
    }
  double total = 0;
  for (std::size_t i = 0; i < grid.nodes(); ++i) {
    total += whole.mass[i];
    EXPECT_NEAR(by_colour.mass[i], whole.mass[i], 1e-12 * (1 + whole.mass[i]));
    EXPECT_NEAR(by_colour.momentum[i][0], whole.momentum[i][0], 1e-12 * (1 + whole.mass[i]));
    EXPECT_NEAR(by_colour.force[i][1], whole.force[i][1], 1e-11 * (1 + whole.mass[i]));
  }
  EXPECT_NEAR(total, 2.0 * static_cast<double>(P.size()), 1e-9 * total);  // the weights sum to one
}

// The blow-up scan over threads finds the particle one scan finds: the first non-finite one, else
// the first of the fastest.
TEST(ParticleScan, ThreadsFindTheSameParticle) {
  auto P = scattered<2>(10000, 11);
  P.v[7000] = Vec<2>(0, 30), P.v[9000] = Vec<2>(-30, 0);  // equally fast: the first counts
  const auto one = ParticleScan<2>::of(P), three = ParticleScan<2>::of(P, 3);
  EXPECT_TRUE(three.finite);
  EXPECT_EQ(three.index, 7000u);
  EXPECT_EQ(three.index, one.index);
  EXPECT_EQ(three.speed, one.speed);
  P.x[8000][1] = std::numeric_limits<double>::quiet_NaN();
  P.v[2500][0] = std::numeric_limits<double>::infinity();
  const auto bad = ParticleScan<2>::of(P, 3);
  EXPECT_FALSE(bad.finite);
  EXPECT_EQ(bad.index, 2500u);
  EXPECT_EQ(ParticleScan<2>::of(P).index, 2500u);
  EXPECT_EQ(ParticleScan<2>::of(Particles<2>{}, 3).speed, 0.0);
}

}  // namespace
}  // namespace suite::mpm2grid
