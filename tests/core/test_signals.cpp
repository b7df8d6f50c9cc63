// SIGUSR1 asks for a checkpoint, SIGTERM for checkpoint-and-stop; the poll agrees over ranks
// even when the signal reached one rank only.
#include <gtest/gtest.h>

#include <csignal>

#include "core/errors.hpp"
#include "core/run/signals.hpp"

namespace {

TEST(Signals, UsrOneRequestsCheckpointTermRequestsStop) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  suite::SignalWatcher w;
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::none);
  if (comm.is_root()) std::raise(SIGUSR1);
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::checkpoint);
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::none) << "poll clears the request";
  if (comm.rank() == comm.size() - 1) {
    std::raise(SIGTERM);
    std::raise(SIGUSR1);  // a weaker request does not downgrade a pending stop
    EXPECT_EQ(w.last_signal(), SIGUSR1);
  }
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::checkpoint_and_stop);
}

TEST(Signals, OnlyOneWatcherAtATime) {
  suite::SignalWatcher w;
  EXPECT_THROW(suite::SignalWatcher second, suite::LibraryError);
}

}  // namespace
