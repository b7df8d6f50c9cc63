#pragma once
// Point-to-point traffic between the ranks of a decomposition, as two collectives over plain
// arrays of trivially copyable values: all_to_all() (each rank sends its own list to every other
// rank: counts by MPI_Alltoall, data by MPI_Alltoallv) and all_gather() (every rank's list on
// every rank: MPI_Allgatherv). Both return what arrived by source rank, so callers process it in
// rank order and the result does not depend on message timing. Lists of one rank may be empty.
#include <mpi.h>

#include <climits>
#include <cstddef>
#include <cstring>
#include <string>
#include <numeric>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"

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
// others sent to this one (its own list to itself included). COLLECTIVE.
template <class T>
std::vector<std::vector<T>> all_to_all(const mpi::Comm& comm, const std::vector<std::vector<T>>& send) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto ranks = static_cast<std::size_t>(comm.size());
  if (send.size() != ranks) throw LibraryError("all_to_all: one list per rank expected");
  std::vector<int> send_counts(ranks), recv_counts(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    const std::size_t bytes = send[r].size() * sizeof(T);
    if (bytes > INT_MAX) throw LibraryError("all_to_all: more than 2 GiB for one rank; use more ranks");
    send_counts[r] = static_cast<int>(bytes);
  }
  SUITE_MPI_CHECK(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm.raw()));
  const auto send_displs = detail::displacements(send_counts, "all_to_all");
  const auto recv_displs = detail::displacements(recv_counts, "all_to_all");
  std::vector<char> out(static_cast<std::size_t>(send_displs.back() + send_counts.back()));
  for (std::size_t r = 0; r < ranks; ++r)
    if (!send[r].empty())
      std::memcpy(out.data() + send_displs[r], send[r].data(), static_cast<std::size_t>(send_counts[r]));
  std::vector<char> in(static_cast<std::size_t>(recv_displs.back() + recv_counts.back()));
  SUITE_MPI_CHECK(MPI_Alltoallv(out.data(), send_counts.data(), send_displs.data(), MPI_BYTE, in.data(),
                                recv_counts.data(), recv_displs.data(), MPI_BYTE, comm.raw()));
  return detail::split<T>(in, recv_counts, recv_displs);
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
  SUITE_MPI_CHECK(MPI_Allgatherv(mine.data(), count, MPI_BYTE, in.data(), counts.data(), displs.data(), MPI_BYTE,
                                 comm.raw()));
  return detail::split<T>(in, counts, displs);
}

}  // namespace suite::mpm2grid
