#pragma once
// The halo of a rank's grid (docs/methods/mpm2grid.md, "Decomposition and performance design"). A rank's
// grid holds the blocks its particles' stencils touch: the ones it owns and, where its particles
// sit within two cells of another rank's blocks, some of that rank's ("ghost" blocks: the 2-cell
// halo of cubic B-splines). Per step:
//   reverse(): after P2G, every ghost block's node values are added into the owner's copy, so
//              the owner holds the complete sums (mass, momentum, force, drag);
//   forward(): after the grid solve, the owner's results (velocities) overwrite the ghost copies,
//              so G2P reads the same node values on every rank.
// The reverse sums send only the nodes with values (the ones the holder's particles reach: on
// Table 3.4 example 2 the halo's bytes fell 3.6-fold), and the velocities go back to just those
// (forward_touched()). A block's node bits travel as the bytes of one double.
// plan() sets up who sends what: each rank tells each owner which of its blocks it holds as
// ghosts, and the owner activates any of them its own particles do not touch. Blocks travel in
// the ghost holder's order and are summed in rank order: the sums do not depend on timing.
#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "solvers/mpm2grid/decomposition/block_owners.hpp"
#include "solvers/mpm2grid/decomposition/exchange.hpp"
#include "solvers/mpm2grid/decomposition/wait_clock.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

template <int Dim>
class HaloExchange {
 public:
  static constexpr int kNodes = BlockGrid<Dim>::kNodes;

  // The time blocked in MPI calls goes to `wait`, which must outlive the exchange.
  explicit HaloExchange(WaitClock& wait) : wait_(&wait) {}

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
    const auto wanted = all_to_all(comm, keys, wait_);
    for (std::size_t r = 0; r < ranks; ++r)
      for (const auto key : wanted[r]) shared_[r].push_back(grid.activate(BlockGrid<Dim>::unkey(key)));
    sent_.assign(ranks, {});
    received_.assign(ranks, {});
    for (std::size_t r = 0; r < ranks; ++r) {
      sent_[r].assign(ghosts_[r].size(), 0);
      received_[r].assign(shared_[r].size(), 0);
    }
    owned_.assign(grid.blocks(), 1);
    for (const auto& list : ghosts_)
      for (const int b : list) owned_[static_cast<std::size_t>(b)] = 0;
  }

  // Per block of the planned grid: 1 when this rank owns it.
  const std::vector<char>& owned() const { return owned_; }
  // Bytes and messages this rank has sent in reverse() and forward() calls since the last take_*().
  long long take_bytes() { return std::exchange(bytes_, 0); }
  long long take_messages() { return std::exchange(messages_, 0); }

  // pack(slot, double* out) writes `width` doubles of a ghost node; add(slot, const double* in)
  // adds them into the owned node. Only the nodes with a value other than zero travel (adding
  // zero changes no sum): per ghost block a word of node bits, then those nodes' values. The
  // nodes sent are remembered until the next plan(): they are the nodes this rank's particles
  // reach, the ones forward_touched() sends back. COLLECTIVE.
  template <class Pack, class Add>
  void reverse(const mpi::Comm& comm, int width, Pack&& pack, Add&& add) {
    move(comm, width, Mode::nonzero, ghosts_, shared_, pack, add);
  }
  // pack(slot, out) writes `width` doubles of an owned node; set(slot, in) stores them in the
  // ghost copy. Every node of the ghost blocks. COLLECTIVE.
  template <class Pack, class Set>
  void forward(const mpi::Comm& comm, int width, Pack&& pack, Set&& set) {
    move(comm, width, Mode::all, shared_, ghosts_, pack, set);
  }
  // The same for the ghost nodes that had a value in this step's reverse() sums (the nodes the
  // holder's particles reach with a weight above zero): the others are read, if at all, with
  // weight zero. COLLECTIVE.
  template <class Pack, class Set>
  void forward_touched(const mpi::Comm& comm, int width, Pack&& pack, Set&& set) {
    move(comm, width, Mode::touched, shared_, ghosts_, pack, set);
  }

 private:
  using Mask = std::uint64_t;  // one bit per node of a block
  static_assert(kNodes <= 64, "a block's nodes must fit the bits of a Mask");
  enum class Mode {
    all,      // every node of every block
    nonzero,  // a Mask per block, then the nodes with a value other than zero (reverse sums)
    touched,  // the nodes of this step's reverse masks, no Mask (both sides know them)
  };

  // One message each way per neighbour (a rank with blocks in either list), point to point:
  // receivers post for the most a message can hold and check what came. The buffers are kept
  // between calls (no page faults for fresh memory every exchange), and what arrived is
  // unpacked in rank order once all of it is in, so sums do not depend on message timing.
  template <class Pack, class Unpack>
  void move(const mpi::Comm& comm, int width, Mode mode, const std::vector<std::vector<int>>& from,
            const std::vector<std::vector<int>>& to, Pack& pack, Unpack& unpack) {
    const auto ranks = static_cast<std::size_t>(comm.size());
    const std::size_t w = static_cast<std::size_t>(width);
    const std::size_t per_block = kNodes * w + (mode == Mode::nonzero ? 1 : 0);  // most doubles per block
    // In touched mode the sender sends the masks it received, the receiver expects the ones it sent.
    auto& send_masks = mode == Mode::touched ? received_ : sent_;
    auto& recv_masks = mode == Mode::touched ? sent_ : received_;
    std::size_t send_total = 0, recv_total = 0;
    for (std::size_t r = 0; r < ranks; ++r) send_total += from[r].size() * per_block, recv_total += to[r].size() * per_block;
    send_.resize(send_total);
    recv_.resize(recv_total);
    requests_.clear();
    recv_starts_.clear();
    constexpr int kTag = 7301;
    double* in = recv_.data();
    for (std::size_t r = 0; r < ranks; ++r) {
      const std::size_t n = to[r].size() * per_block;
      if (n == 0) continue;
      if (n > INT_MAX) throw LibraryError("HaloExchange: more than 2^31 node values from one rank; use more ranks");
      recv_starts_.push_back(in);
      SUITE_MPI_CHECK(MPI_Irecv(in, static_cast<int>(n), MPI_DOUBLE, static_cast<int>(r), kTag, comm.raw(),
                                &requests_.emplace_back()));
      in += n;
    }
    double* out = send_.data();
    std::size_t sends = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      if (from[r].empty()) continue;
      if (from[r].size() * per_block > INT_MAX)
        throw LibraryError("HaloExchange: more than 2^31 node values for one rank; use more ranks");
      double* start = out;
      for (std::size_t k = 0; k < from[r].size(); ++k) {
        const long first = static_cast<long>(from[r][k]) * kNodes;
        if (mode == Mode::all) {
          for (int i = 0; i < kNodes; ++i, out += w) pack(first + i, out);
        } else if (mode == Mode::touched) {
          const Mask mask = send_masks[r][k];
          for (int i = 0; i < kNodes; ++i)
            if (mask >> i & 1) pack(first + i, out), out += w;
        } else {
          double* word = out++;
          Mask mask = 0;
          for (int i = 0; i < kNodes; ++i) {
            pack(first + i, out);
            if (std::any_of(out, out + w, [](double v) { return v != 0; })) mask |= Mask{1} << i, out += w;
          }
          std::memcpy(word, &mask, sizeof mask);
          send_masks[r][k] |= mask;
        }
      }
      const auto n = static_cast<std::size_t>(out - start);
      SUITE_MPI_CHECK(MPI_Isend(start, static_cast<int>(n), MPI_DOUBLE, static_cast<int>(r), kTag, comm.raw(),
                                &requests_.emplace_back()));
      ++sends;
      ++messages_;
      bytes_ += static_cast<long long>(n * sizeof(double));
    }
    const std::size_t receives = requests_.size() - sends;
    statuses_.resize(requests_.size());
    wait_->time([&] {
      SUITE_MPI_CHECK(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), statuses_.data()));
    });
    for (std::size_t k = 0, r = 0; k < receives; ++r) {
      if (to[r].empty()) continue;
      int count = 0;
      SUITE_MPI_CHECK(MPI_Get_count(&statuses_[k], MPI_DOUBLE, &count));
      const double* next = recv_starts_[k++];
      const double* end = next + count;
      for (std::size_t b = 0; b < to[r].size(); ++b) {
        const long first = static_cast<long>(to[r][b]) * kNodes;
        Mask mask = ~Mask{0};
        if (mode == Mode::touched) mask = recv_masks[r][b];
        if (mode == Mode::nonzero) {
          if (next == end) throw LibraryError("HaloExchange: a neighbour sent fewer blocks than planned");
          std::memcpy(&mask, next++, sizeof mask);
          recv_masks[r][b] |= mask;
        }
        for (int i = 0; i < kNodes; ++i) {
          if (!(mask >> i & 1)) continue;
          if (end - next < width) throw LibraryError("HaloExchange: a neighbour sent fewer node values than planned");
          unpack(first + i, next);
          next += w;
        }
      }
      if (next != end) throw LibraryError("HaloExchange: a neighbour sent more node values than planned");
    }
  }

  WaitClock* wait_;
  std::vector<std::vector<int>> ghosts_;  // per owner rank: this rank's ghost blocks of it, in sent order
  std::vector<std::vector<int>> shared_;  // per rank: this rank's blocks it holds as ghosts, in its order
  std::vector<char> owned_;
  // Per rank, per block of ghosts_ (sent_) and of shared_ (received_): the nodes that travelled
  // in this step's reverse sums, reset by plan().
  std::vector<std::vector<Mask>> sent_, received_;
  std::vector<double> send_, recv_;  // kept between exchanges
  std::vector<const double*> recv_starts_;  // where each receive's values begin in recv_
  std::vector<MPI_Request> requests_;
  std::vector<MPI_Status> statuses_;
  long long bytes_ = 0, messages_ = 0;
};

}  // namespace suite::mpm2grid
