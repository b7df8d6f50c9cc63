#include "solvers/mpm2grid/decomposition/domain_decomposition.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/errors.hpp"
#include "solvers/mpm2grid/decomposition/diffuse_partition.hpp"
#include "solvers/mpm2grid/decomposition/exchange.hpp"
#include "solvers/mpm2grid/decomposition/partition.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"

namespace suite::mpm2grid {

template <int Dim>
Index<Dim> DomainDecomposition<Dim>::home(const Vec<Dim>& x) const {
  return BlockGrid<Dim>::home_block(x, grid_->spacing());
}

template <int Dim>
void DomainDecomposition<Dim>::prepare(BlockGrid<Dim>& grid) {
  std::vector<BlockOwners::Key> unowned;
  for (std::size_t b = 0; b < grid.blocks(); ++b) {
    const auto key = BlockGrid<Dim>::key(grid.block_coord(b));
    if (owners_.owner(key) < 0) unowned.push_back(key);
  }
  stats_.claimed_blocks += wait_.time([&] { return owners_.claim(comm_, unowned); });
  halo_.plan(comm_, grid, owners_);
}

template <int Dim>
void DomainDecomposition<Dim>::sum_to_owners(NodeFields<Dim>& f) {
  halo_.reverse(
      comm_, 3 + 2 * Dim,  // mass, drag, pressure sum, momentum, force
      [&](long i, double* out) {
        out[0] = f.mass[i], out[1] = f.drag[i], out[2] = f.pressure[i];
        for (int d = 0; d < Dim; ++d) out[3 + d] = f.momentum[i][d], out[3 + Dim + d] = f.force[i][d];
      },
      [&](long i, const double* in) {
        f.mass[i] += in[0], f.drag[i] += in[1], f.pressure[i] += in[2];
        for (int d = 0; d < Dim; ++d) f.momentum[i][d] += in[3 + d], f.force[i][d] += in[3 + Dim + d];
      });
  stats_.halo_bytes += halo_.take_bytes();
  stats_.halo_messages += halo_.take_messages();
}

template <int Dim>
void DomainDecomposition<Dim>::sum_forces_to_owners(NodeFields<Dim>& f) {
  halo_.reverse(
      comm_, Dim, [&](long i, double* out) { std::copy_n(f.force[i].data(), Dim, out); },
      [&](long i, const double* in) {
        for (int d = 0; d < Dim; ++d) f.force[i][d] += in[d];
      });
  stats_.halo_bytes += halo_.take_bytes();
  stats_.halo_messages += halo_.take_messages();
}

template <int Dim>
void DomainDecomposition<Dim>::copy_to_ghosts(NodeFields<Dim>& soil, NodeFields<Dim>& water) {
  // Only the ghost nodes this rank's particles reach (the ones its reverse sums sent): G2P reads
  // the others, if at all, with weight zero.
  halo_.forward_touched(
      comm_, 2 * Dim + 1,
      [&](long i, double* out) {
        for (int d = 0; d < Dim; ++d) out[d] = soil.velocity[i][d], out[Dim + d] = water.velocity[i][d];
        out[2 * Dim] = water.mass[i];
      },
      [&](long i, const double* in) {
        for (int d = 0; d < Dim; ++d) soil.velocity[i][d] = in[d], water.velocity[i][d] = in[Dim + d];
        water.mass[i] = in[2 * Dim];
      });
  stats_.halo_bytes += halo_.take_bytes();
  stats_.halo_messages += halo_.take_messages();
}

template <int Dim>
void DomainDecomposition<Dim>::copy_to_ghosts(std::vector<long>& per_slot) {
  // Node numbers below 2^53 travel exactly as doubles.
  halo_.forward(
      comm_, 1, [&](long i, double* out) { out[0] = static_cast<double>(per_slot[static_cast<std::size_t>(i)]); },
      [&](long i, const double* in) { per_slot[static_cast<std::size_t>(i)] = static_cast<long>(in[0]); });
  stats_.halo_bytes += halo_.take_bytes();
  stats_.halo_messages += halo_.take_messages();
}

template <int Dim>
void DomainDecomposition<Dim>::copy_to_ghosts(std::vector<double>& per_slot) {
  halo_.forward(
      comm_, 1, [&](long i, double* out) { out[0] = per_slot[static_cast<std::size_t>(i)]; },
      [&](long i, const double* in) { per_slot[static_cast<std::size_t>(i)] = in[0]; });
  stats_.halo_bytes += halo_.take_bytes();
  stats_.halo_messages += halo_.take_messages();
}

template <int Dim>
void DomainDecomposition<Dim>::migrate(Particles<Dim>& water, Particles<Dim>& soil,
                                       const std::array<std::vector<char>, 2>* left_home) {
  using Key = BlockOwners::Key;
  // Particles in group order (transfer/particle_order.hpp) come in runs with one home block:
  // its owner is looked up once a run.
  Key last_key = 0;
  int last_owner = -1;
  bool looked_up = false;
  const auto owner_of = [&](const Vec<Dim>& x) {
    const Key key = BlockGrid<Dim>::key(home(x));
    if (!looked_up || key != last_key) last_key = key, last_owner = owners_.owner(key), looked_up = true;
    return last_owner;
  };
  // The particles that leave this rank, with their destinations: the owners of their home
  // blocks. Blocks without one yet are claimed first (every rank takes part), then their
  // particles are looked up again. A particle that kept its home block since the last migration
  // stays: every one was at its owner then, and owners change only in partition(), which is
  // followed by a migration of all.
  const int me = comm_.rank();
  std::vector<Key> unowned;
  const std::array<Particles<Dim>*, 2> species{&water, &soil};
  for (std::size_t k = 0; k < 2; ++k) {
    auto& leaving = leaving_[k];
    leaving.clear();
    const Particles<Dim>& P = *species[k];
    const std::size_t tracked = left_home ? std::min((*left_home)[k].size(), P.size()) : 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (p < tracked && !(*left_home)[k][p]) continue;
      const int owner = owner_of(P.x[p]);
      if (owner == me) continue;
      if (owner < 0) unowned.push_back(last_key);
      leaving.push_back({p, owner});
    }
  }
  std::sort(unowned.begin(), unowned.end());
  unowned.erase(std::unique(unowned.begin(), unowned.end()), unowned.end());
  stats_.claimed_blocks += wait_.time([&] { return owners_.claim(comm_, unowned); });
  looked_up = false;  // the claims gave owners to blocks that had none
  if (!unowned.empty())
    for (std::size_t k = 0; k < 2; ++k) {
      for (auto& l : leaving_[k])
        if (l.to < 0) l.to = owner_of(species[k]->x[l.p]);
      std::erase_if(leaving_[k], [&](const Leaving& l) { return l.to == me; });  // claimed here
    }

  // One message per destination that receives particles (none to the others: a rank sends to
  // its neighbours, not to every rank): the number of water particles, then the water's and the
  // soil's packed states (each message's size reserved: growing it would hold up to three times
  // its particles at once).
  const auto ranks = static_cast<std::size_t>(comm_.size());
  constexpr auto kPacked = static_cast<std::size_t>(Particles<Dim>::kPacked);
  std::vector<std::size_t> sizes(ranks, 0);
  for (const auto& leaving : leaving_)
    for (const auto& l : leaving) sizes[static_cast<std::size_t>(l.to)] += kPacked;
  std::vector<std::vector<double>> send(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (sizes[r] == 0) continue;
    send[r].reserve(1 + sizes[r]);
    send[r].push_back(0.0);
  }
  for (std::size_t k = 0; k < 2; ++k) {
    for (const auto& l : leaving_[k]) {
      auto& to = send[static_cast<std::size_t>(l.to)];
      species[k]->pack(l.p, to);
      if (k == 0) to[0] += 1;
    }
    stats_.migrated += static_cast<long long>(leaving_[k].size());
    sent_[k].clear();
    for (const auto& l : leaving_[k]) sent_[k].push_back(l.p);
    species[k]->remove(sent_[k]);
  }
  for (std::size_t r = 0; r < ranks; ++r)
    if (static_cast<int>(r) != me && !send[r].empty()) {
      stats_.migration_bytes += static_cast<long long>(send[r].size() * sizeof(double));
      ++stats_.migration_messages;
    }
  const auto received = all_to_all(comm_, send, &wait_);
  send = {};  // the particles that left, sent: freed before the arrivals are added
  std::array<std::size_t, 2> arriving{water.size(), soil.size()};
  for (const auto& from : received) {
    if (from.empty()) continue;  // nothing from that rank
    const auto water_count = static_cast<std::size_t>(from[0]);
    if ((from.size() - 1) % kPacked != 0 || water_count > (from.size() - 1) / kPacked)
      throw LibraryError("particle migration: a rank sent a partial particle");
    arriving[0] += water_count;
    arriving[1] += (from.size() - 1) / kPacked - water_count;
  }
  water.reserve(arriving[0]);
  soil.reserve(arriving[1]);
  for (const auto& from : received) {
    if (from.empty()) continue;
    const auto water_count = static_cast<std::size_t>(from[0]);
    for (std::size_t k = 1, n = 0; k < from.size(); k += kPacked, ++n)
      (n < water_count ? water : soil).add_packed(from.data() + k);
  }
}

template <int Dim>
std::unordered_map<BlockOwners::Key, std::array<long long, 2>> DomainDecomposition<Dim>::home_counts(
    const Particles<Dim>& water, const Particles<Dim>& soil) const {
  // The particles come in runs with one home block (group order, transfer/particle_order.hpp):
  // a run's count is added once to its block's.
  std::unordered_map<BlockOwners::Key, std::array<long long, 2>> count;
  const std::array<const Particles<Dim>*, 2> species{&soil, &water};
  for (std::size_t s = 0; s < 2; ++s) {
    const Particles<Dim>& P = *species[s];
    long long run = 0;
    BlockOwners::Key run_key = 0;
    const auto flush = [&] {
      if (run > 0) count[run_key][s] += run;
    };
    for (std::size_t p = 0; p < P.size(); ++p) {
      const auto key = BlockGrid<Dim>::key(home(P.x[p]));
      if (key != run_key) flush(), run = 0, run_key = key;
      ++run;
    }
    flush();
  }
  return count;
}

template <int Dim>
bool DomainDecomposition<Dim>::balance(long long step, Particles<Dim>& water, Particles<Dim>& soil, bool force) {
  if (!force) {
    if (s_.check_every <= 0 || step % s_.check_every != 0) return false;
    // Per quantity (partition.hpp): this rank's work and its largest block's, every rank's in
    // one exchange.
    std::vector<long long> mine(2 * kQuantities, 0);
    for (const auto& [key, soil_water] : home_counts(water, soil)) {
      const BlockWeight w = weight(soil_water);
      for (std::size_t q = 0; q < kQuantities; ++q)
        mine[q] += w[q], mine[kQuantities + q] = std::max(mine[kQuantities + q], w[q]);
    }
    const auto all = wait_.time([&] { return all_gather(comm_, mine); });
    std::array<double, kQuantities> worst;
    worst.fill(1);
    bool due = false;
    for (std::size_t s = 0; s < kQuantities; ++s) {
      long long total = 0, most = 0, block = 0;
      for (const auto& r : all) total += r[s], most = std::max(most, r[s]), block = std::max(block, r[kQuantities + s]);
      // A quantity too small to spread (fewer than 64 particles a rank) is no measure of the load.
      if (total < 64LL * comm_.size()) continue;
      const double mean = static_cast<double>(total) / comm_.size(), ratio = static_cast<double>(most) / mean;
      worst[s] = ratio;
      // Due above the threshold, unless the excess is within one block: no partition of whole
      // blocks does much better, and repartitioning then would repeat at every check (example 2
      // at 0.25 m on 8 ranks, blocks of up to 64 particles against 226 water particles a rank:
      // 45 repartitions in 3 s).
      due = due || (ratio > s_.threshold(s) && static_cast<double>(most) - mean > static_cast<double>(block));
    }
    stats_.imbalance = std::max(worst[kSoil], worst[kWater]);
    stats_.wet_soil_imbalance = worst[kWetSoil];
    if (!due) return false;
    ++stats_.rebalances;
  }
  partition(water, soil, force);
  const long long before = stats_.migrated;
  migrate(water, soil);
  if (!force) stats_.rebalance_migrated += stats_.migrated - before;
  return true;
}

template <int Dim>
void DomainDecomposition<Dim>::partition(const Particles<Dim>& water, const Particles<Dim>& soil, bool first) {
  // This rank's blocks in use (its particles' stencils) with the particles whose home they are.
  struct Entry {
    BlockOwners::Key key;
    long long soil, water;
  };
  BlockGrid<Dim> touched(grid_->spacing());
  touch_blocks(water, touched);
  touch_blocks(soil, touched);
  const auto homes = home_counts(water, soil);
  std::vector<Entry> mine;
  mine.reserve(touched.blocks());
  for (std::size_t b = 0; b < touched.blocks(); ++b) {
    const auto key = BlockGrid<Dim>::key(touched.block_coord(b));
    const auto it = homes.find(key);
    mine.push_back(it == homes.end() ? Entry{key, 0, 0} : Entry{key, it->second[0], it->second[1]});
  }
  // Every rank's, merged by block in key order (a block at a border is in use on several ranks).
  std::map<BlockOwners::Key, std::array<long long, 2>> blocks;
  for (const auto& from : all_gather(comm_, mine))
    for (const auto& e : from) {
      auto& w = blocks[e.key];
      w[0] += e.soil, w[1] += e.water;
    }
  std::vector<BlockOwners::Key> keys;
  std::vector<Index<Dim>> coords;
  std::vector<BlockWeight> weights;
  std::vector<int> previous;
  std::vector<long long> work;
  for (const auto& [key, w] : blocks) {
    keys.push_back(key);
    coords.push_back(BlockGrid<Dim>::unkey(key));
    weights.push_back(weight(w));
    previous.push_back(owners_.owner(key));
    work.push_back(w[0] + w[1]);
  }
  // The new owners are found on rank 0 and broadcast: every rank gets the same table (the last
  // entry says whether the diffusion found them). A failure there stops every rank (none is
  // left waiting in the broadcast).
  std::vector<int> ranks(keys.size() + 1, 0);
  std::string problem;
  const auto started = std::chrono::steady_clock::now();
  if (comm_.is_root()) try {
      const BlockGraph graph = block_graph<Dim>(coords);
      std::optional<Diffused> diffused;
      if (!first && s_.diffuse)
        diffused =
            diffuse_partition(graph, weights, previous, comm_.size(), s_.diffusion_target(), s_.diffusion_accept());
      if (diffused) {
        std::copy(diffused->part.begin(), diffused->part.end(), ranks.begin());
        ranks.back() = 1;
      } else {
        const auto parts =
            keep_ranks(fresh_partition(graph, weights, comm_.size(), s_.diffusion_target(), s_.diffusion_accept()),
                       previous, work, comm_.size());
        std::copy(parts.begin(), parts.end(), ranks.begin());
      }
    } catch (const std::exception& e) {
      problem = e.what();
      if (problem.empty()) problem = "the partition failed";
    }
  if (!first && comm_.is_root())
    stats_.partition_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  comm_.broadcast(problem);
  if (!problem.empty()) throw LibraryError("partitioning the grid blocks: " + problem);
  SUITE_MPI_CHECK(MPI_Bcast(ranks.data(), static_cast<int>(ranks.size()), MPI_INT, 0, comm_.raw()));
  stats_.diffused += ranks.back();
  ranks.pop_back();
  owners_.assign(keys, ranks);
}

template <int Dim>
std::vector<long long> DomainDecomposition<Dim>::owned_keys() const {
  const auto keys = owners_.owned_by(comm_.rank());
  return {keys.begin(), keys.end()};
}

template <int Dim>
void DomainDecomposition<Dim>::restore(const std::vector<long long>& mine) {
  owners_.restore(comm_, std::vector<BlockOwners::Key>(mine.begin(), mine.end()));
}

template class DomainDecomposition<2>;
template class DomainDecomposition<3>;

}  // namespace suite::mpm2grid
