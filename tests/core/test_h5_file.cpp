// Collective parallel-HDF5 writes read back bit for bit: uneven row counts, a rank with no
// rows, 1D and 2D arrays, integer types, attributes.
#include <gtest/gtest.h>

#include "core/io/h5_file.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::io::H5File;

TEST(H5File, CollectiveRowsWriteReadsBackExactly) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  const int r = comm.rank();
  // Rank r holds 3r+1 rows of 3 columns, except that the last rank of several holds none.
  const long long rows = (comm.size() > 1 && r == comm.size() - 1) ? 0 : 3 * r + 1;
  std::vector<double> xyz;
  std::vector<long long> ids;
  for (long long i = 0; i < rows; ++i) {
    for (int c = 0; c < 3; ++c) xyz.push_back(1000.0 * r + 10.0 * i + c + 0.125);
    ids.push_back(100 * r + i);
  }
  suite::io::RowRange range;
  {
    H5File f(comm, dir / "step.h5", H5File::Mode::create);
    range = f.write_rows<double>("/particles/position", xyz, 3);
    f.write_rows<long long>("/particles/id", ids);
    const std::vector<double> origin{0.5, -1.0};
    f.write_replicated<double>("/grid/origin", origin);
    f.set_attribute("/", "time", 12.5);
    f.set_attribute("/particles", "unit", std::string("m"));
    f.set_attribute("/", "step", 7LL);
  }
  EXPECT_EQ(range.count, rows);
  EXPECT_EQ(range.total, comm.sum(rows));
  H5File f(comm, dir / "step.h5", H5File::Mode::read);
  EXPECT_EQ(f.shape("/particles/position"), (std::vector<long long>{range.total, 3}));
  EXPECT_EQ(f.read_rows<double>("/particles/position", range.offset, range.count), xyz);
  EXPECT_EQ(f.read_rows<long long>("/particles/id", range.offset, range.count), ids);
  // Every rank sees the whole array in rank order.
  const auto all_ids = f.read_all<long long>("/particles/id");
  long long k = 0;
  for (int q = 0; q < comm.size(); ++q) {
    const long long n = (comm.size() > 1 && q == comm.size() - 1) ? 0 : 3 * q + 1;
    for (long long i = 0; i < n; ++i) EXPECT_EQ(all_ids[static_cast<std::size_t>(k++)], 100 * q + i);
  }
  EXPECT_EQ(f.read_all<double>("/grid/origin"), (std::vector<double>{0.5, -1.0}));
  EXPECT_DOUBLE_EQ(f.get_attribute_double("/", "time"), 12.5);
  EXPECT_EQ(f.get_attribute_string("/particles", "unit"), "m");
  EXPECT_EQ(f.get_attribute_int("/", "step"), 7);
  EXPECT_TRUE(f.exists("/particles/id"));
  EXPECT_FALSE(f.exists("/nothing/here"));
}

TEST(H5File, EmptyGlobalArrayAndBadPaths) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  {
    H5File f(comm, dir / "empty.h5", H5File::Mode::create);
    auto r = f.write_rows<double>("/nothing", std::vector<double>{});
    EXPECT_EQ(r.total, 0);
  }
  H5File f(comm, dir / "empty.h5", H5File::Mode::read);
  EXPECT_TRUE(f.read_all<double>("/nothing").empty());
  EXPECT_NE(suite::testing::input_error_of([&] { f.shape("/missing"); }).find("has no dataset '/missing'"),
            std::string::npos);
  EXPECT_NE(suite::testing::input_error_of([&] {
              H5File g(comm, dir / "absent.h5", H5File::Mode::read);
            }).find("cannot open HDF5 file"),
            std::string::npos);
}

}  // namespace
