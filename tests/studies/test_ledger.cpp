// The evaluation ledger: lines round-trip (non-finite responses as null), a torn last line is
// ignored on reading and cut before appending, a corrupt middle line is an error naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/mpi/comm.hpp"
#include "studies/ledger/ledger.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;

TEST(Ledger, RoundTripTornLineAndCorruption) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto path = dir / "ledger.jsonl";
  {
    Ledger l(path);
    l.append({1, {0.1, 2.0}, input_hash({"a", "b"}, {0.1, 2.0}), true, "", {3.5, std::nan("")}, 0.01, "h"});
    l.append({2, {0.2, 2.0}, input_hash({"a", "b"}, {0.2, 2.0}), false, "it broke", {std::nan(""), 1.0}, 0.02, "h"});
  }
  auto e = Ledger::read(path);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].inputs[0], 0.1);
  EXPECT_TRUE(std::isnan(e[0].responses[1]));
  EXPECT_FALSE(e[1].ok);
  EXPECT_EQ(e[1].reason, "it broke");
  EXPECT_NE(e[0].hash, e[1].hash);
  EXPECT_EQ(e[0].hash, input_hash({"a", "b"}, {0.1, 2.0})) << "stable";
  EXPECT_NE(input_hash({"a", "b"}, {0.1, 2.0}), input_hash({"b", "a"}, {0.1, 2.0})) << "names count";
  // A kill mid-write leaves half a line: reading ignores it, appending cuts it first.
  std::ofstream(path, std::ios::app) << "{\"eval_id\": 3, \"inp";
  EXPECT_EQ(Ledger::read(path).size(), 2u);
  {
    Ledger l(path);
    l.append({3, {0.3, 2.0}, "x", true, "", {1.0, 1.0}, 0.0, "h"});
  }
  ASSERT_EQ(Ledger::read(path).size(), 3u);
  EXPECT_EQ(Ledger::read(path)[2].eval_id, 3);
  // A broken line that is not the last one is not silently dropped.
  std::ofstream(path, std::ios::app) << "garbage\n{\"eval_id\": 4}\n";
  EXPECT_NE(suite::testing::input_error_of([&] { Ledger::read(path); }).find("ledger.jsonl:4"), std::string::npos);
}

}  // namespace
