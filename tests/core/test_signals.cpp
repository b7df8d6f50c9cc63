// SIGUSR1 asks for a checkpoint, SIGTERM for checkpoint-and-stop; the poll agrees over ranks
// even when the signal reached one rank only.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "core/run/signals.hpp"
#include "tests/support/test_dirs.hpp"

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

// The request files act like the signals, once each, whichever rank polls; rank 0 looks.
TEST(Signals, RequestFilesActOnceLikeTheSignals) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  suite::SignalWatcher w(dir);
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::none);
  const auto touch = [&](const char* name) {
    if (comm.is_root()) std::ofstream(dir / name) << "\n";
    comm.barrier();
  };
  touch("checkpoint_now");
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::checkpoint);
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::none) << "the file is removed when seen";
  touch("stop");
  touch("checkpoint_now");
  EXPECT_EQ(w.poll(comm), suite::SignalRequest::checkpoint_and_stop) << "the stronger request wins";
  EXPECT_FALSE(std::filesystem::exists(dir / "stop"));
  EXPECT_FALSE(std::filesystem::exists(dir / "checkpoint_now"));
  EXPECT_EQ(w.last_signal(), 0) << "no signal was sent";
}

TEST(Signals, OnlyOneWatcherAtATime) {
  suite::SignalWatcher w;
  EXPECT_THROW(suite::SignalWatcher second, suite::LibraryError);
}

}  // namespace
