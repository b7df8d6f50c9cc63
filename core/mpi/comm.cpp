#include "core/mpi/comm.hpp"

#include "core/errors.hpp"

namespace suite::mpi {

struct Comm::Owned {
  explicit Owned(MPI_Comm c) : comm(c) {}
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  MPI_Comm comm;
  ~Owned() {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }
};

Comm::Comm(MPI_Comm raw) : Comm(raw, nullptr) {}

Comm::Comm(MPI_Comm raw, std::shared_ptr<Owned> owner) : raw_(raw), owner_(std::move(owner)) {
  SUITE_MPI_CHECK(MPI_Comm_set_errhandler(raw_, MPI_ERRORS_RETURN));
  SUITE_MPI_CHECK(MPI_Comm_rank(raw_, &rank_));
  SUITE_MPI_CHECK(MPI_Comm_size(raw_, &size_));
}

Comm Comm::dup() const {
  MPI_Comm c = MPI_COMM_NULL;
  SUITE_MPI_CHECK(MPI_Comm_dup(raw_, &c));
  return Comm(c, std::make_shared<Owned>(c));
}

Comm Comm::split(int color, int key) const {
  MPI_Comm c = MPI_COMM_NULL;
  SUITE_MPI_CHECK(MPI_Comm_split(raw_, color, key, &c));
  return Comm(c, std::make_shared<Owned>(c));
}

Comm Comm::split_shared() const {
  MPI_Comm c = MPI_COMM_NULL;
  SUITE_MPI_CHECK(MPI_Comm_split_type(raw_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &c));
  return Comm(c, std::make_shared<Owned>(c));
}

void Comm::barrier() const {
  SUITE_MPI_CHECK(MPI_Barrier(raw_));
}

namespace {
template <class T>
T reduce(MPI_Comm c, T v, MPI_Datatype t, MPI_Op op) {
  T out{};
  SUITE_MPI_CHECK(MPI_Allreduce(&v, &out, 1, t, op, c));
  return out;
}
}  // namespace

double Comm::sum(double v) const {
  return reduce(raw_, v, MPI_DOUBLE, MPI_SUM);
}
long long Comm::sum(long long v) const {
  return reduce(raw_, v, MPI_LONG_LONG, MPI_SUM);
}
double Comm::max(double v) const {
  return reduce(raw_, v, MPI_DOUBLE, MPI_MAX);
}
long long Comm::max(long long v) const {
  return reduce(raw_, v, MPI_LONG_LONG, MPI_MAX);
}
double Comm::min(double v) const {
  return reduce(raw_, v, MPI_DOUBLE, MPI_MIN);
}
bool Comm::any(bool v) const {
  return reduce(raw_, v ? 1 : 0, MPI_INT, MPI_MAX) != 0;
}
bool Comm::all(bool v) const {
  return reduce(raw_, v ? 1 : 0, MPI_INT, MPI_MIN) != 0;
}

long long Comm::exclusive_prefix_sum(long long v) const {
  long long out = 0;
  SUITE_MPI_CHECK(MPI_Exscan(&v, &out, 1, MPI_LONG_LONG, MPI_SUM, raw_));
  return rank_ == 0 ? 0 : out;  // MPI leaves rank 0's result undefined
}

std::vector<long long> Comm::all_gather(long long v) const {
  std::vector<long long> out(static_cast<std::size_t>(size_));
  SUITE_MPI_CHECK(MPI_Allgather(&v, 1, MPI_LONG_LONG, out.data(), 1, MPI_LONG_LONG, raw_));
  return out;
}

std::vector<std::string> Comm::all_gather(const std::string& s) const {
  const int n = static_cast<int>(s.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
  SUITE_MPI_CHECK(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, raw_));
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    offsets[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  SUITE_MPI_CHECK(MPI_Allgatherv(s.data(), n, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR, raw_));
  std::vector<std::string> out;
  for (int r = 0; r < size_; ++r)
    out.push_back(all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(r)]),
                             static_cast<std::size_t>(counts[static_cast<std::size_t>(r)])));
  return out;
}

void Comm::all_reduce(std::span<double> values, Reduction op) const {
  const MPI_Op mpi_op = op == Reduction::sum ? MPI_SUM : (op == Reduction::min ? MPI_MIN : MPI_MAX);
  SUITE_MPI_CHECK(
      MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, mpi_op, raw_));
}

void Comm::broadcast(std::string& s, int root) const {
  long long n = static_cast<long long>(s.size());
  SUITE_MPI_CHECK(MPI_Bcast(&n, 1, MPI_LONG_LONG, root, raw_));
  s.resize(static_cast<std::size_t>(n));
  SUITE_MPI_CHECK(MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, root, raw_));
}

}  // namespace suite::mpi
