// The pieces of the domain decomposition (decomposition/) that need no second rank: the METIS
// partition of a block graph balances both species' particle counts within the tolerance it is
// given (1%, plus one block) and keeps each part in one piece, and spreads the wet soil (10%,
// plus one block); keep_ranks renames parts so that work stays where it was; block keys
// round-trip; a particle's packed state round-trips exactly.
// The decomposition over ranks as a whole is tested end to end (1 vs 2 ranks,
// run_ranks_agree.sh, and the decomposed steps in test_consistent_drag.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <stdexcept>

#include "solvers/mpm2grid/decomposition/diffuse_partition.hpp"
#include "solvers/mpm2grid/decomposition/partition.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/particle_order.hpp"

namespace suite::mpm2grid {
namespace {

TEST(Partition, BalancesBothSpeciesOverConnectedParts) {
  // A 24 x 6 strip of blocks: soil in the left third (100 particles a block), water elsewhere
  // (30 a block). A split by block count would give one rank all the soil.
  std::vector<Index<2>> blocks;
  std::vector<BlockWeight> weights;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 24; ++i) {
      blocks.push_back({i, j});
      weights.push_back(i < 8 ? BlockWeight{100, 0, 0} : BlockWeight{0, 30, 0});
    }
  for (const int parts : {2, 3, 4}) {
    const auto part = partition_blocks(block_graph<2>(blocks), weights, parts);
    std::vector<std::array<long long, 2>> load(static_cast<std::size_t>(parts), {0, 0});
    for (std::size_t b = 0; b < blocks.size(); ++b)
      for (int s = 0; s < 2; ++s)
        load[static_cast<std::size_t>(part[b])][static_cast<std::size_t>(s)] += weights[b][static_cast<std::size_t>(s)];
    for (int s = 0; s < 2; ++s) {
      const double mean = (s == 0 ? 4800.0 : 2880.0) / parts;
      for (const auto& l : load)
        EXPECT_LE(static_cast<double>(l[static_cast<std::size_t>(s)]), 1.01 * mean + 100)
            << parts << " parts, species " << s;
    }
  }
}

TEST(Partition, SpreadsTheWetSoilOverTheParts) {
  // A 64 x 32 strip of blocks: soil below (60 particles a block), water above (20), and where
  // they meet a row of blocks home to both, whose soil is the wet soil (64 x 60 = 3,840
  // particles: 240 a part in 16 parts). Balancing the particle counts alone cuts the strip into
  // columns of which few hold much of that row; with the wet soil as a third constraint every
  // part holds its share within the wet soil's tolerance (10%) and one block, and the
  // particles stay within theirs (1%) and one block.
  std::vector<Index<2>> blocks;
  std::vector<BlockWeight> weights;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 64; ++i) {
      blocks.push_back({i, j});
      const long long soil = j <= 15 ? 60 : 0, water = j >= 15 ? 20 : 0;
      weights.push_back({soil, water, wet_soil(soil, water)});
    }
  constexpr int parts = 16;
  const BlockGraph graph = block_graph<2>(blocks);
  // Each part's load of each quantity from weights w, under the partition given w.
  const auto loads = [&](const std::vector<BlockWeight>& w) {
    const auto part = fresh_partition(graph, w, parts, 1.0167, 1.025);
    std::vector<BlockWeight> load(parts, BlockWeight{});
    for (std::size_t b = 0; b < blocks.size(); ++b)
      for (std::size_t q = 0; q < kQuantities; ++q) load[static_cast<std::size_t>(part[b])][q] += weights[b][q];
    return load;
  };
  const BlockWeight total{64 * 16 * 60, 64 * 17 * 20, 64 * 60};
  for (const auto& l : loads(weights))
    for (std::size_t q = 0; q < kQuantities; ++q)
      EXPECT_LE(static_cast<double>(l[q]), kTolerance[q] * static_cast<double>(total[q]) / parts + 60)
          << "quantity " << q;
  // Without the third constraint (no wet soil given) some part holds at least twice its share.
  auto dry = weights;
  for (auto& w : dry) w[kWetSoil] = 0;
  long long most = 0;
  for (const auto& l : loads(dry)) most = std::max(most, l[kWetSoil]);
  EXPECT_GE(most, 2 * total[kWetSoil] / parts);
}

TEST(Partition, KeepRanksFollowsTheWork) {
  // Parts 0 and 1 swapped against the old owners: renaming gives every block its old rank back.
  const std::vector<int> parts{1, 1, 1, 0, 0, 0}, previous{0, 0, 0, 1, 1, 1};
  const std::vector<long long> work(6, 10);
  EXPECT_EQ(keep_ranks(parts, previous, work, 2), previous);
  // No previous owner: the parts keep their names.
  EXPECT_EQ(keep_ranks(parts, std::vector<int>(6, -1), work, 2), parts);
  // Three parts, old work all on rank 0: the part holding most of it stays there, the others
  // take ranks 1 and 2.
  const auto renamed = keep_ranks({2, 2, 2, 0, 1, 1}, {0, 0, 0, 0, -1, -1}, {5, 5, 5, 1, 1, 1}, 3);
  EXPECT_EQ(renamed[0], 0);
  EXPECT_EQ(std::set<int>(renamed.begin(), renamed.end()), (std::set<int>{0, 1, 2}));
}

TEST(BlockGrid, KeysRoundTrip) {
  for (const Index<3>& b : {Index<3>{0, 0, 0}, Index<3>{-5, 17, -1000}, Index<3>{1 << 19, -(1 << 20), 3}})
    EXPECT_EQ(BlockGrid<3>::unkey(BlockGrid<3>::key(b)), b);
  for (const Index<2>& b : {Index<2>{-1, 2}, Index<2>{123456, -654321}})
    EXPECT_EQ(BlockGrid<2>::unkey(BlockGrid<2>::key(b)), b);
  // A particle's home block holds the lower corner of its cell (node floor(x / h)).
  BlockGrid<2> grid(0.5);
  EXPECT_EQ(grid.home_block(Vec<2>(1.99, -0.01)), (Index<2>{0, -1}));
  EXPECT_EQ(grid.home_block(Vec<2>(2.0, 0.0)), (Index<2>{1, 0}));
}

TEST(Particles, PackedStateRoundTrips) {
  Particles<3> a, b;
  a.add(Vec<3>(1, 2, 3), Vec<3>(-1, 0.5, 2), 7.5, 0.125);
  a.C[0] = Mat<3>::Random(), a.F[0] = Mat<3>::Random();
  a.J[0] = 0.97, a.log_jp[0] = -0.01, a.saturation[0] = 0.4;
  std::vector<double> buffer;
  a.pack(0, buffer);
  ASSERT_EQ(buffer.size(), static_cast<std::size_t>(Particles<3>::kPacked));
  b.add_packed(buffer.data());
  EXPECT_EQ(b.x[0], a.x[0]);
  EXPECT_EQ(b.v[0], a.v[0]);
  EXPECT_EQ(b.C[0], a.C[0]);
  EXPECT_EQ(b.F[0], a.F[0]);
  EXPECT_EQ(b.mass[0], a.mass[0]);
  EXPECT_EQ(b.volume0[0], a.volume0[0]);
  EXPECT_EQ(b.J[0], a.J[0]);
  EXPECT_EQ(b.log_jp[0], a.log_jp[0]);
  EXPECT_EQ(b.saturation[0], a.saturation[0]);
  EXPECT_EQ(b.id[0], a.id[0]);
}

// Ids number the particles in the order add() made them, travel with them through a reordering
// and a removal, and are not given twice.
TEST(Particles, IdsFollowTheirParticles) {
  Particles<2> P;
  for (int i = 0; i < 6; ++i) P.add(Vec<2>(i, 0), Vec<2>(0, i), 1.0 + i, 1.0);
  EXPECT_EQ(P.id, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5}));
  const std::vector<std::size_t> order{5, 3, 1, 0, 2, 4};
  P.for_each_array([&](auto& values) { apply_order(values, order); });
  P.remove({static_cast<std::size_t>(std::find(P.id.begin(), P.id.end(), 3) - P.id.begin())});
  ASSERT_EQ(P.size(), 5u);
  for (std::size_t p = 0; p < P.size(); ++p) {
    EXPECT_EQ(P.x[p][0], static_cast<double>(P.id[p]));
    EXPECT_EQ(P.mass[p], 1.0 + static_cast<double>(P.id[p]));
  }
  P.add(Vec<2>(9, 9), Vec<2>::Zero(), 1.0, 1.0);
  EXPECT_EQ(P.id.back(), 6);
}

// Removing particles fills each place with the last particle that stays: the others keep their
// places, ids and states; the caller's arrays follow.
TEST(Particles, RemoveFillsPlacesFromTheEnd) {
  Particles<2> P;
  for (int i = 0; i < 7; ++i) P.add(Vec<2>(i, 0), Vec<2>(0, i), 1.0 + i, 1.0);
  std::vector<int> along{10, 11, 12, 13, 14, 15, 16};
  P.remove({1, 4, 5}, along);
  EXPECT_EQ(P.id, (std::vector<std::int64_t>{0, 6, 2, 3}));
  EXPECT_EQ(along, (std::vector<int>{10, 16, 12, 13}));
  for (std::size_t p = 0; p < P.size(); ++p) {
    EXPECT_EQ(P.x[p][0], static_cast<double>(P.id[p]));
    EXPECT_EQ(P.mass[p], 1.0 + static_cast<double>(P.id[p]));
  }
  P.remove({}, along);
  EXPECT_EQ(P.size(), 4u);
  P.remove({0, 1, 2, 3}, along);
  EXPECT_EQ(P.size(), 0u);
  EXPECT_TRUE(along.empty());
  std::vector<int> short_list{1};
  EXPECT_THROW(P.remove({}, short_list), std::logic_error);
}

// Group order: each group's particles consecutive, in their own order within a group, groups in
// block order; particles that already come in few enough runs are left as they are.
TEST(ParticleOrder, GroupsBecomeConsecutiveAndStable) {
  const std::vector<int> group{2, 0, 2, 1, 0, 2, 1, 0};
  const auto order = group_order(group, 3);
  EXPECT_EQ(order, (std::vector<std::size_t>{1, 4, 7, 3, 6, 0, 2, 5}));
  // 3 groups in 3 runs, and 4 groups in 5 or 8 runs (at most twice as many): no reordering;
  // 4 groups in 9 runs: reordered.
  EXPECT_TRUE(group_order({0, 0, 1, 1, 2}, 3).empty());
  EXPECT_TRUE(group_order({3, 3, 0, 1, 1, 2, 3}, 4).empty());
  EXPECT_TRUE(group_order({3, 0, 1, 3, 0, 2, 3, 1}, 4).empty());
  EXPECT_FALSE(group_order({3, 0, 1, 3, 0, 2, 3, 1, 2}, 4).empty());
}

}  // namespace
}  // namespace suite::mpm2grid
