#pragma once
// The halo of a rank's grid (docs/methods/mpm2grid.md, "Decomposition and performance design"). A rank's
// grid holds the blocks its particles' stencils touch: the ones it owns and, where its particles
// sit within two cells of another rank's blocks, some of that rank's ("ghost" blocks: the 2-cell
// halo of cubic B-splines). Per step:
//   reverse(): after P2G, every ghost block's node values are added into the owner's copy, so
//              the owner holds the complete sums (mass, momentum, force, drag);
//   forward(): after the grid solve, the owner's results (velocities) overwrite the ghost copies,
//              so G2P reads the same node values on every rank.
// plan() sets up who sends what: each rank tells each owner which of its blocks it holds as
// ghosts, and the owner activates any of them its own particles do not touch. Blocks travel in
// the ghost holder's order and are summed in rank order: the sums do not depend on timing.
#include <mpi.h>

#include <climits>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "solvers/mpm2grid/decomposition/block_owners.hpp"
#include "solvers/mpm2grid/decomposition/exchange.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

template <int Dim>
class HaloExchange {
 public:
  static constexpr int kNodes = BlockGrid<Dim>::kNodes;

  // COLLECTIVE. Every block of `grid` must have an owner. May add blocks to `grid` (owned ones
  // that only other ranks' particles touch).
  void plan(const mpi::Comm& comm, BlockGrid<Dim>& grid, const BlockOwners& owners) {
    const auto ranks = static_cast<std::size_t>(comm.size());
    ghosts_.assign(ranks, {});
    shared_.assign(ranks, {});
    std::vector<std::vector<typename BlockGrid<Dim>::Key>> keys(ranks);
    for (std::size_t b = 0; b < grid.blocks(); ++b) {
      const auto key = BlockGrid<Dim>::key(grid.block_coord(b));
      const int r = owners.owner(key);
      if (r < 0) throw LibraryError("HaloExchange::plan: a grid block has no owner (claim it first)");
      if (r == comm.rank()) continue;
      ghosts_[static_cast<std::size_t>(r)].push_back(static_cast<int>(b));
      keys[static_cast<std::size_t>(r)].push_back(key);
    }
    const auto wanted = all_to_all(comm, keys);
    for (std::size_t r = 0; r < ranks; ++r)
      for (const auto key : wanted[r]) shared_[r].push_back(grid.activate(BlockGrid<Dim>::unkey(key)));
    owned_.assign(grid.blocks(), 1);
    for (const auto& list : ghosts_)
      for (const int b : list) owned_[static_cast<std::size_t>(b)] = 0;
  }

  // Per block of the planned grid: 1 when this rank owns it.
  const std::vector<char>& owned() const { return owned_; }
  // Bytes this rank has sent in reverse() and forward() calls since the last take_bytes().
  long long take_bytes() { return std::exchange(bytes_, 0); }

  // pack(slot, double* out) writes `width` doubles of a ghost node; add(slot, const double* in)
  // adds them into the owned node. COLLECTIVE.
  template <class Pack, class Add>
  void reverse(const mpi::Comm& comm, int width, Pack&& pack, Add&& add) {
    move(comm, width, ghosts_, shared_, pack, add);
  }
  // pack(slot, out) writes `width` doubles of an owned node; set(slot, in) stores them in the
  // ghost copy. COLLECTIVE.
  template <class Pack, class Set>
  void forward(const mpi::Comm& comm, int width, Pack&& pack, Set&& set) {
    move(comm, width, shared_, ghosts_, pack, set);
  }

 private:
  // One message each way per neighbour (a rank with blocks in either list), point to point: the
  // sizes follow from the plan on both sides, so no counts travel. The buffers are kept between
  // calls (no page faults for fresh memory every exchange), and what arrived is unpacked in rank
  // order once all of it is in, so sums do not depend on message timing.
  template <class Pack, class Unpack>
  void move(const mpi::Comm& comm, int width, const std::vector<std::vector<int>>& from,
            const std::vector<std::vector<int>>& to, Pack& pack, Unpack& unpack) {
    const auto ranks = static_cast<std::size_t>(comm.size());
    const auto block = static_cast<std::size_t>(kNodes) * static_cast<std::size_t>(width);
    std::size_t send_total = 0, recv_total = 0;
    for (std::size_t r = 0; r < ranks; ++r) send_total += from[r].size() * block, recv_total += to[r].size() * block;
    send_.resize(send_total);
    recv_.resize(recv_total);
    requests_.clear();
    constexpr int kTag = 7301;
    double* in = recv_.data();
    for (std::size_t r = 0; r < ranks; ++r) {
      const std::size_t n = to[r].size() * block;
      if (n == 0) continue;
      if (n > INT_MAX) throw LibraryError("HaloExchange: more than 2^31 node values from one rank; use more ranks");
      SUITE_MPI_CHECK(MPI_Irecv(in, static_cast<int>(n), MPI_DOUBLE, static_cast<int>(r), kTag, comm.raw(),
                                &requests_.emplace_back()));
      in += n;
    }
    double* out = send_.data();
    std::size_t sends = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      const std::size_t n = from[r].size() * block;
      if (n == 0) continue;
      if (n > INT_MAX) throw LibraryError("HaloExchange: more than 2^31 node values for one rank; use more ranks");
      double* start = out;
      for (const int b : from[r])
        for (int k = 0; k < kNodes; ++k, out += width) pack(static_cast<long>(b) * kNodes + k, out);
      SUITE_MPI_CHECK(MPI_Isend(start, static_cast<int>(n), MPI_DOUBLE, static_cast<int>(r), kTag, comm.raw(),
                                &requests_.emplace_back()));
      ++sends;
      bytes_ += static_cast<long long>(n * sizeof(double));
    }
    const std::size_t receives = requests_.size() - sends;
    statuses_.resize(requests_.size());
    SUITE_MPI_CHECK(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), statuses_.data()));
    for (std::size_t k = 0, r = 0; k < receives; ++r) {
      if (to[r].empty()) continue;
      int count = 0;
      SUITE_MPI_CHECK(MPI_Get_count(&statuses_[k++], MPI_DOUBLE, &count));
      if (static_cast<std::size_t>(count) != to[r].size() * block)
        throw LibraryError("HaloExchange: a neighbour sent another number of node values than planned");
    }
    const double* next = recv_.data();
    for (std::size_t r = 0; r < ranks; ++r)
      for (const int b : to[r])
        for (int k = 0; k < kNodes; ++k, next += width) unpack(static_cast<long>(b) * kNodes + k, next);
  }

  std::vector<std::vector<int>> ghosts_;  // per owner rank: this rank's ghost blocks of it, in sent order
  std::vector<std::vector<int>> shared_;  // per rank: this rank's blocks it holds as ghosts, in its order
  std::vector<char> owned_;
  std::vector<double> send_, recv_;  // kept between exchanges
  std::vector<MPI_Request> requests_;
  std::vector<MPI_Status> statuses_;
  long long bytes_ = 0;
};

}  // namespace suite::mpm2grid
