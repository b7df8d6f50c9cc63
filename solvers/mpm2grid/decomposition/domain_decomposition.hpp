#pragma once
// The domain decomposition of an mpm2grid run over the ranks of a communicator
// (docs/methods/mpm2grid.md, "Decomposition and performance design"; issue 3, item 5). Ranks own grid
// blocks (block_owners.hpp); a particle belongs to the rank owning its home block (the block
// holding the lower corner of its cell). Per step:
//   prepare()         the grid of this rank's particles' stencils: blocks no rank owns yet are
//                     claimed, the halo is planned (halo_exchange.hpp);
//   sum_to_owners()   after each species' P2G: a reverse halo sum of its mass, momentum, force,
//                     drag coefficients and pressure sums;
//   copy_to_ghosts()  after the grid solve and the boundary conditions: one forward copy of both
//                     species' velocities and the water's mass (the soil's saturation reads it);
//   migrate()         after the particles moved: each goes to the rank owning its new home block.
// balance() measures the load every `check_every` steps: the particle counts of each species per
// rank, and with `balance_wet_soil` the wet soil (partition.hpp), each from the particles whose
// home blocks a rank owns (deterministic, unlike timings, so a restart repeats the same
// decisions bit for bit). When the most loaded rank holds more than `imbalance` times the mean
// of a quantity (the wet soil: threshold()), and more than the largest block of it above it
// (no partition of whole blocks does much better than one block), blocks on the ranks' borders
// move between neighbouring ranks until every quantity is within a third of that margin of its
// mean (the wet soil: its tolerance), or half a block (diffuse_partition.hpp); where that does
// not come within half the margin (and for the first distribution, or with `repartition =
// fresh`) the blocks in use are partitioned afresh with METIS (fresh_partition), each part kept
// on the rank that held most of its work. Then the particles move to their new owners.
// No rank holds the whole grid or solution: only its blocks, its ghosts and the owner table
// (one integer per block).
#include <algorithm>
#include <array>
#include <unordered_map>
#include <vector>

#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/decomposition/block_owners.hpp"
#include "solvers/mpm2grid/decomposition/halo_exchange.hpp"
#include "solvers/mpm2grid/decomposition/partition.hpp"
#include "solvers/mpm2grid/decomposition/wait_clock.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

struct DecompositionSettings {
  int check_every = 20;    // steps between load measurements
  double imbalance = 1.05;  // rebalance above this ratio of the largest to the mean particle count
  bool diffuse = true;     // rebalance by moving border blocks (false: a fresh METIS partition)
  // Also balance the wet soil (partition.hpp: the consistent drag's matrix rows), measured and
  // partitioned as a third quantity beside the particle counts. A scene with the consistent drag
  // sets it unless it says otherwise (scene.cpp); the other drags have no use for it.
  bool balance_wet_soil = false;
  // What a diffusive rebalance aims at: a third of the margin (1.0167 for 1.05), at least
  // METIS's 1%; and accepts: half the margin (a fresh partition moves most particles).
  double diffusion_target() const { return std::max(1.01, 1 + (imbalance - 1) / 3); }
  double diffusion_accept() const { return std::max(diffusion_target(), 1 + (imbalance - 1) / 2); }
  // The load above which quantity q (partition.hpp) is out of balance: `imbalance`; for the wet
  // soil, which a partition may leave 10% above its mean (kTolerance), at least twice that margin
  // (so that what the partition leaves does not rebalance at the next check).
  double threshold(std::size_t q) const {
    return q == kWetSoil ? std::max(imbalance, 1 + 2 * (kTolerance[q] - 1)) : imbalance;
  }
};

// What this rank did, summed since the run (or its restart) began.
struct DecompositionStats {
  long long rebalances = 0;       // partitions after the first
  long long diffused = 0;         // of those, by moving border blocks (the others by METIS)
  long long rebalance_migrated = 0;  // particles sent to other ranks by those
  double partition_seconds = 0;      // rank 0's time finding their owner tables (0 elsewhere)
  long long halo_bytes = 0;       // sent in reverse sums and forward copies
  long long halo_messages = 0;    // point-to-point messages of those
  long long migration_bytes = 0;  // sent with migrating particles
  long long migration_messages = 0;  // point-to-point messages of those (one per rank receiving some)
  long long migrated = 0;         // particles sent to other ranks
  long long claimed_blocks = 0;   // blocks first reached between partitions (counted on every rank)
  double imbalance = 1;           // at the last measurement: the particles' (soil's or water's)
  double wet_soil_imbalance = 1;  // and the wet soil's, where it is balanced
};

template <int Dim>
class DomainDecomposition {
 public:
  // `grid` is the caller's grid, whose spacing places particles in blocks; it must outlive the
  // decomposition.
  DomainDecomposition(const mpi::Comm& comm, const DecompositionSettings& settings, const BlockGrid<Dim>& grid)
      : comm_(comm), s_(settings), grid_(&grid), halo_(wait_) {}
  DomainDecomposition(const DomainDecomposition&) = delete;  // the halo holds on to wait_
  DomainDecomposition& operator=(const DomainDecomposition&) = delete;

  const mpi::Comm& comm() const { return comm_; }
  const DecompositionStats& stats() const { return stats_; }
  // Seconds this rank has spent blocked in MPI calls (waiting for messages and collectives),
  // cumulative: the decomposition's own, and those the simulation times through it (its
  // reductions over the ranks).
  WaitClock& waited() const { return wait_; }

  // COLLECTIVE. `grid` holds the blocks this rank's particles touch; blocks are claimed and
  // added (owned ones that other ranks' particles touch) as the halo needs.
  void prepare(BlockGrid<Dim>& grid);
  // Per block of the prepared grid: 1 where this rank owns it.
  const std::vector<char>& owned_blocks() const { return halo_.owned(); }

  // COLLECTIVE. Owners get the complete sums of one species' mass, momentum, force (before
  // gravity), drag and pressure sums.
  void sum_to_owners(NodeFields<Dim>& species);
  // COLLECTIVE. The same for the force sums alone (the implicit forces' stresses).
  void sum_forces_to_owners(NodeFields<Dim>& species);
  // COLLECTIVE. Ghost nodes get their owners' velocities (both species) and water mass: the
  // nodes this rank's particles reached in this step's sum_to_owners() calls (the others keep
  // their partial values; G2P reads them with weight zero).
  void copy_to_ghosts(NodeFields<Dim>& soil, NodeFields<Dim>& water);
  // COLLECTIVE. Ghost nodes get their owners' values of a per-slot integer (the drag solve's
  // node numbers).
  void copy_to_ghosts(std::vector<long>& per_slot);
  // COLLECTIVE. The same for a per-slot value (the water's node pressure).
  void copy_to_ghosts(std::vector<double>& per_slot);

  // COLLECTIVE. Every particle goes to the rank owning its home block (claimed if new). With
  // `left_home` (per water and soil particle, 1 where the particle's home block changed since the
  // last migration), only those particles and the ones after the lists' ends (new ones) are
  // looked up.
  void migrate(Particles<Dim>& water, Particles<Dim>& soil,
               const std::array<std::vector<char>, 2>* left_home = nullptr);
  // Drops from a per-particle array of the caller's the entries of the particles the last
  // migrate() sent away from species k (0 water, 1 soil), as migrate() did from the particles;
  // the caller sizes it for the ones received.
  template <class T>
  void drop_sent(std::size_t k, std::vector<T>& values) const {
    remove_at(sent_[k], values);
  }
  // COLLECTIVE. Partitions when forced (the first distribution) or when the measurement due at
  // this step finds the load above the threshold; then migrates. True when it partitioned.
  bool balance(long long step, Particles<Dim>& water, Particles<Dim>& soil, bool force = false);

  // The owner table for checkpoints: the blocks this rank owns, and the table rebuilt from every
  // rank's. restore() is COLLECTIVE.
  std::vector<long long> owned_keys() const;
  void restore(const std::vector<long long>& mine);

 private:
  Index<Dim> home(const Vec<Dim>& x) const;
  // The soil and water particles of this rank per block they are home to.
  std::unordered_map<BlockOwners::Key, std::array<long long, 2>> home_counts(const Particles<Dim>& water,
                                                                             const Particles<Dim>& soil) const;
  // A block's work (partition.hpp) from its soil and water particles.
  BlockWeight weight(const std::array<long long, 2>& soil_water) const {
    return {soil_water[0], soil_water[1], s_.balance_wet_soil ? wet_soil(soil_water[0], soil_water[1]) : 0};
  }
  // `first`: the first distribution (METIS, whatever the settings).
  void partition(const Particles<Dim>& water, const Particles<Dim>& soil, bool first);

  mpi::Comm comm_;
  DecompositionSettings s_;
  const BlockGrid<Dim>* grid_;  // the simulation's grid (for its spacing)
  BlockOwners owners_;
  mutable WaitClock wait_;  // bookkeeping, also of the const reductions timed through waited()
  HaloExchange<Dim> halo_;
  DecompositionStats stats_;
  struct Leaving {
    std::size_t p;  // the particle's index
    int to;         // its new owner
  };
  std::array<std::vector<Leaving>, 2> leaving_;  // migrate()'s lists (water, soil), kept for their capacity
  std::array<std::vector<std::size_t>, 2> sent_;  // the indices the last migrate() sent away, ascending
};

extern template class DomainDecomposition<2>;
extern template class DomainDecomposition<3>;

}  // namespace suite::mpm2grid
