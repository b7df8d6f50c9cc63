// Checkpoints: bit-for-bit round trip per rank, atomic appearance, and refusal of files from
// another solver, format, suite version or rank count.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstring>
#include <random>

#include "core/checkpoint/checkpoint.hpp"
#include "core/run/build_info.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

namespace ckpt = suite::checkpoint;
using suite::testing::input_error_of;

struct Counters {
  long long step;
  double dt;
  int rebalance_count;
};

ckpt::Header header(long long step) {
  return {"mpm2grid", 3, step, 0.001 * step, "", 0};
}

TEST(Checkpoint, RoundTripIsBitForBitPerRank) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  std::mt19937_64 rng(1234 + comm.rank());
  std::uniform_real_distribution<double> u(-1e300, 1e300);
  std::vector<double> x(static_cast<std::size_t>(17 * comm.rank() + 3));
  for (auto& v : x) v = u(rng);
  x.push_back(-0.0);
  x.push_back(std::numeric_limits<double>::denorm_min());
  std::vector<long long> ids(static_cast<std::size_t>(comm.rank()));  // rank 0: empty block
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<long long>(rng());
  const Counters c{42, 1.0 / 3.0, comm.rank()};

  const auto path = ckpt::file_name(dir, "checkpoint", 42);
  {
    ckpt::Writer w(comm, path, header(42));
    w.write<double>("x", x);
    w.write<long long>("ids", ids);
    w.write_bytes("counters", std::as_bytes(std::span(&c, 1)));
    w.commit();
  }
  ckpt::Reader r(comm, path, "mpm2grid", 3);
  EXPECT_EQ(r.header().step, 42);
  EXPECT_EQ(r.header().time, 0.042);
  EXPECT_EQ(r.header().ranks, comm.size());
  const auto x2 = r.read<double>("x");
  ASSERT_EQ(x2.size(), x.size());
  EXPECT_EQ(std::memcmp(x2.data(), x.data(), x.size() * sizeof(double)), 0) << "bitwise, including -0";
  EXPECT_EQ(r.read<long long>("ids"), ids);
  const auto bytes = r.read_bytes("counters");
  ASSERT_EQ(bytes.size(), sizeof(Counters));
  Counters c2{};
  std::memcpy(&c2, bytes.data(), sizeof c2);
  EXPECT_EQ(c2.step, c.step);
  EXPECT_EQ(c2.dt, c.dt);
  EXPECT_EQ(c2.rebalance_count, c.rebalance_count);
  EXPECT_NE(input_error_of([&] { r.read<double>("absent"); }).find("has no array 'absent'"), std::string::npos);
}

TEST(Checkpoint, UncommittedWriteLeavesThePreviousCheckpointAlone) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  const std::vector<double> v{1, 2, 3};
  {
    ckpt::Writer w(comm, ckpt::file_name(dir, "checkpoint", 10), header(10));
    w.write<double>("v", v);
    w.commit();
  }
  {
    ckpt::Writer w(comm, ckpt::file_name(dir, "checkpoint", 20), header(20));
    w.write<double>("v", v);
    // the run dies here: no commit
  }
  comm.barrier();
  EXPECT_FALSE(std::filesystem::exists(ckpt::file_name(dir, "checkpoint", 20)));
  EXPECT_FALSE(std::filesystem::exists(ckpt::file_name(dir, "checkpoint", 20).string() + ".tmp"));
  EXPECT_EQ(ckpt::latest(dir, "checkpoint").value(), ckpt::file_name(dir, "checkpoint", 10));
  EXPECT_FALSE(ckpt::latest(dir, "other").has_value());
}

TEST(Checkpoint, PruneKeepsTheNewest) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  for (long long s : {5, 15, 25}) {
    ckpt::Writer w(comm, ckpt::file_name(dir, "chk", s), header(s));
    w.commit();
  }
  if (comm.is_root()) ckpt::prune(dir, "chk", 2);
  comm.barrier();
  EXPECT_FALSE(std::filesystem::exists(ckpt::file_name(dir, "chk", 5)));
  EXPECT_TRUE(std::filesystem::exists(ckpt::file_name(dir, "chk", 15)));
  EXPECT_EQ(ckpt::latest(dir, "chk").value(), ckpt::file_name(dir, "chk", 25));
}

TEST(Checkpoint, StaleCheckpointsOfAnEarlierRunAreDiscarded) {
  // An earlier run left steps 100 and 150; a new run restarting from step 50 must not have its
  // own checkpoints pruned in favour of them, nor see them as the latest.
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  for (long long s : {50, 100, 150}) {
    ckpt::Writer w(comm, ckpt::file_name(dir, "checkpoint", s), header(s));
    w.commit();
  }
  EXPECT_EQ(ckpt::latest(comm, dir, "checkpoint").value(), ckpt::file_name(dir, "checkpoint", 150));
  int removed = 0;
  if (comm.is_root()) removed = ckpt::discard_after(dir, "checkpoint", 50);
  comm.barrier();
  EXPECT_EQ(comm.sum(static_cast<long long>(removed)), 2);
  EXPECT_EQ(ckpt::latest(comm, dir, "checkpoint").value(), ckpt::file_name(dir, "checkpoint", 50));
  {
    ckpt::Writer w(comm, ckpt::file_name(dir, "checkpoint", 60), header(60));
    w.commit();
  }
  if (comm.is_root()) ckpt::prune(dir, "checkpoint", 1);
  comm.barrier();
  EXPECT_EQ(ckpt::latest(comm, dir, "checkpoint").value(), ckpt::file_name(dir, "checkpoint", 60));
  if (comm.is_root()) ckpt::discard_after(dir, "checkpoint", -1);  // a fresh start
  comm.barrier();
  EXPECT_FALSE(ckpt::latest(comm, dir, "checkpoint").has_value());
}

TEST(Checkpoint, RefusesOtherSolverFormatOrVersion) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  const auto path = ckpt::file_name(dir, "checkpoint", 1);
  {
    ckpt::Writer w(comm, path, header(1));
    w.commit();
  }
  EXPECT_NE(input_error_of([&] {
              ckpt::Reader r(comm, path, "carving", 3);
            }).find("was written by 'mpm2grid', not 'carving'"),
            std::string::npos);
  const std::string fmt_msg = input_error_of([&] { ckpt::Reader r(comm, path, "mpm2grid", 4); });
  EXPECT_NE(fmt_msg.find("has format 3 from suite " + suite::build_info().version + "; this build reads format 4"),
            std::string::npos)
      << fmt_msg;
  // The same file stamped by another suite version.
  if (comm.is_root()) {
    hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    H5Adelete(f, "suite_version");
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 5);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(f, "suite_version", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, "9.9.9");
    H5Aclose(a), H5Sclose(sp), H5Tclose(t), H5Fclose(f);
  }
  comm.barrier();
  EXPECT_NE(input_error_of([&] { ckpt::Reader r(comm, path, "mpm2grid", 3); }).find("from suite 9.9.9"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { ckpt::Reader r(comm, dir / "none.h5", "mpm2grid", 3); }).find("does not exist"),
            std::string::npos);
}

TEST(Checkpoint, RefusesAnotherRankCount) {
  suite::mpi::Comm world(MPI_COMM_WORLD);
  if (world.size() < 2) GTEST_SKIP() << "needs 2 ranks to write with one count and read with another";
  const auto dir = suite::testing::scratch_dir(world);
  const auto path = ckpt::file_name(dir, "checkpoint", 7);
  {
    ckpt::Writer w(world, path, header(7));
    w.commit();
  }
  auto alone = world.split(world.rank(), 0);  // one rank each
  const std::string msg = input_error_of([&] { ckpt::Reader r(alone, path, "mpm2grid", 3); });
  EXPECT_NE(msg.find(fmt::format("was written by {} ranks but this run has 1", world.size())), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("srun -n 2"), std::string::npos) << msg;
}

}  // namespace
