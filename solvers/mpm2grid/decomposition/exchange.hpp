#pragma once
// Point-to-point traffic between the ranks of a decomposition, as two collectives over plain
// arrays of trivially copyable values: all_to_all() (each rank sends its own list to every other
// rank: counts by MPI_Alltoall, data point to point; the time blocked in MPI counted in a
// WaitClock when one is given) and all_gather() (every rank's list on
// every rank: MPI_Allgatherv). Both return what arrived by source rank, so callers process it in
// rank order and the result does not depend on message timing. Lists of one rank may be empty.
#include <mpi.h>

#include <climits>
#include <cstddef>
#include <cstring>
#include <numeric>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/decomposition/wait_clock.hpp"

namespace suite::mpm2grid {
namespace detail {

// Byte counts and displacements as MPI's ints; a rank's traffic past 2 GiB is refused.
inline std::vector<int> displacements(const std::vector<int>& counts, const char* what) {
  std::vector<int> displs(counts.size(), 0);
  long long total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = static_cast<int>(total);
    total += counts[r];
    if (total > INT_MAX)
      throw LibraryError(std::string(what) + ": more than 2 GiB to exchange in one call; use more ranks");
  }
  return displs;
}

template <class T>
std::vector<std::vector<T>> split(const std::vector<char>& bytes, const std::vector<int>& counts,
                                  const std::vector<int>& displs) {
  std::vector<std::vector<T>> out(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r) {
    out[r].resize(static_cast<std::size_t>(counts[r]) / sizeof(T));
    if (counts[r] > 0) std::memcpy(out[r].data(), bytes.data() + displs[r], static_cast<std::size_t>(counts[r]));
  }
  return out;
}

}  // namespace detail

// Sends send[r] to rank r (send has comm.size() lists) and returns, by source rank, what the
// others sent to this one (its own list to itself included). COLLECTIVE. The counts go by
// MPI_Alltoall, the lists point to point straight from `send` into the returned lists: no
// contiguous copy on either side (a rank handing out half of all particles, as at the first
// distribution, would hold its share three times over).
template <class T>
std::vector<std::vector<T>> all_to_all(const mpi::Comm& comm, const std::vector<std::vector<T>>& send,
                                       WaitClock* wait = nullptr) {
  static_assert(std::is_trivially_copyable_v<T>);
  constexpr int kTag = 7302;  // not the halo exchange's
  const auto ranks = static_cast<std::size_t>(comm.size());
  const auto me = static_cast<std::size_t>(comm.rank());
  if (send.size() != ranks) throw LibraryError("all_to_all: one list per rank expected");
  std::vector<int> send_counts(ranks), recv_counts(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    const std::size_t bytes = send[r].size() * sizeof(T);
    if (bytes > INT_MAX) throw LibraryError("all_to_all: more than 2 GiB for one rank; use more ranks");
    send_counts[r] = static_cast<int>(bytes);
  }
  WaitClock unused;
  WaitClock& clock = wait ? *wait : unused;
  clock.time(
      [&] { SUITE_MPI_CHECK(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm.raw())); });
  std::vector<std::vector<T>> in(ranks);
  std::vector<MPI_Request> requests;
  requests.reserve(2 * ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (r == me || recv_counts[r] == 0) continue;
    if (recv_counts[r] % static_cast<int>(sizeof(T)) != 0) throw LibraryError("all_to_all: a partial value arrived");
    in[r].resize(static_cast<std::size_t>(recv_counts[r]) / sizeof(T));
    requests.emplace_back();
    SUITE_MPI_CHECK(
        MPI_Irecv(in[r].data(), recv_counts[r], MPI_BYTE, static_cast<int>(r), kTag, comm.raw(), &requests.back()));
  }
  for (std::size_t r = 0; r < ranks; ++r) {
    if (r == me || send_counts[r] == 0) continue;
    requests.emplace_back();
    SUITE_MPI_CHECK(
        MPI_Isend(send[r].data(), send_counts[r], MPI_BYTE, static_cast<int>(r), kTag, comm.raw(), &requests.back()));
  }
  in[me] = send[me];
  clock.time(
      [&] { SUITE_MPI_CHECK(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE)); });
  return in;
}

// Every rank's list, on every rank, by rank. COLLECTIVE.
template <class T>
std::vector<std::vector<T>> all_gather(const mpi::Comm& comm, const std::vector<T>& mine) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t bytes = mine.size() * sizeof(T);
  if (bytes > INT_MAX) throw LibraryError("all_gather: more than 2 GiB from one rank");
  std::vector<int> counts(static_cast<std::size_t>(comm.size()));
  const int count = static_cast<int>(bytes);
  SUITE_MPI_CHECK(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm.raw()));
  const auto displs = detail::displacements(counts, "all_gather");
  std::vector<char> in(static_cast<std::size_t>(displs.back() + counts.back()));
  SUITE_MPI_CHECK(
      MPI_Allgatherv(mine.data(), count, MPI_BYTE, in.data(), counts.data(), displs.data(), MPI_BYTE, comm.raw()));
  return detail::split<T>(in, counts, displs);
}

}  // namespace suite::mpm2grid
