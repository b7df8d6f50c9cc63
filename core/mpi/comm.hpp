#pragma once
// Comm: the communicator every library object takes explicitly.
//
// A Comm either borrows an MPI_Comm (the default) or owns one it created with dup()/split(),
// which it frees when the last copy goes away. It switches its communicator to
// MPI_ERRORS_RETURN: failures come back as codes and go through check_mpi (a LibraryError
// naming the call) instead of aborting inside MPI. Every member that talks to other ranks is
// marked COLLECTIVE: all ranks of the communicator must call it, in the same order.
#include <mpi.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace suite::mpi {

class Comm {
 public:
  explicit Comm(MPI_Comm raw);  // borrows `raw`
  Comm() : Comm(MPI_COMM_SELF) {}

  MPI_Comm raw() const { return raw_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  Comm dup() const;                      // COLLECTIVE; owning
  Comm split(int color, int key) const;  // COLLECTIVE; owning
  Comm split_shared() const;             // COLLECTIVE; owning: the ranks of this node

  void barrier() const;  // COLLECTIVE

  // Reductions over all ranks, result on every rank. COLLECTIVE.
  double sum(double v) const;
  long long sum(long long v) const;
  double max(double v) const;
  long long max(long long v) const;
  double min(double v) const;
  bool any(bool v) const;
  bool all(bool v) const;
  // Exclusive prefix sum: the count of items on ranks below this one. COLLECTIVE.
  long long exclusive_prefix_sum(long long v) const;
  // Every rank's value, gathered to every rank. COLLECTIVE.
  std::vector<long long> all_gather(long long v) const;
  std::vector<std::string> all_gather(const std::string& s) const;
  // Element-wise reduction of equally long arrays, result on every rank. COLLECTIVE.
  enum class Reduction { sum, min, max };
  void all_reduce(std::span<double> values, Reduction op) const;
  // Broadcast from `root`; on other ranks the argument is overwritten. COLLECTIVE.
  void broadcast(std::string& s, int root = 0) const;

 private:
  struct Owned;
  Comm(MPI_Comm raw, std::shared_ptr<Owned> owner);
  MPI_Comm raw_;
  int rank_ = 0;
  int size_ = 1;
  std::shared_ptr<Owned> owner_;  // set when this Comm created the communicator
};

}  // namespace suite::mpi
