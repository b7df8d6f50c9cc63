#include "core/mpi/task_farm.hpp"

#include "core/errors.hpp"

namespace suite::mpi {
namespace {

constexpr int kWorkTag = 11, kResultTag = 12;

void send_id(const Comm& comm, long long id, int to) {
  SUITE_MPI_CHECK(MPI_Send(&id, 1, MPI_LONG_LONG, to, kWorkTag, comm.raw()));
}

}  // namespace

void run_task_farm(const Comm& comm, const std::vector<long>& pending, const std::function<std::string(long)>& work,
                   const std::function<void(const std::string&)>& record) {
  if (comm.rank() == 0) {
    std::size_t next = 0;
    int busy = 0;
    for (int w = 1; w < comm.size(); ++w) {
      if (next < pending.size()) {
        send_id(comm, pending[next++], w);
        ++busy;
      } else {
        send_id(comm, -1, w);
      }
    }
    while (busy > 0) {
      MPI_Status status;
      SUITE_MPI_CHECK(MPI_Probe(MPI_ANY_SOURCE, kResultTag, comm.raw(), &status));
      int length = 0;
      SUITE_MPI_CHECK(MPI_Get_count(&status, MPI_CHAR, &length));
      std::string text(static_cast<std::size_t>(length), '\0');
      SUITE_MPI_CHECK(
          MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kResultTag, comm.raw(), MPI_STATUS_IGNORE));
      if (next < pending.size()) {
        send_id(comm, pending[next++], status.MPI_SOURCE);
      } else {
        send_id(comm, -1, status.MPI_SOURCE);
        --busy;
      }
      record(text);
    }
  } else {
    for (;;) {
      long long id = 0;
      SUITE_MPI_CHECK(MPI_Recv(&id, 1, MPI_LONG_LONG, 0, kWorkTag, comm.raw(), MPI_STATUS_IGNORE));
      if (id < 0) break;
      const std::string text = work(static_cast<long>(id));
      SUITE_MPI_CHECK(MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kResultTag, comm.raw()));
    }
  }
  comm.barrier();
}

}  // namespace suite::mpi
