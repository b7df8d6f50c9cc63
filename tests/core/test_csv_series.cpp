#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/io/csv_series.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CsvSeries, HeaderCarriesUnitsAndRowsAreFlushedAsWritten) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm());
  suite::io::CsvSeries csv(dir / "q.csv", {{"time", "s"}, {"discharge", "m^3/s"}, {"label", ""}});
  csv.append({0.0, 1.5, 3});
  csv.append({0.5, 2.25, 4});
  // Flushed: another reader sees both rows while the writer is still open.
  EXPECT_EQ(read(dir / "q.csv"), "time [s],discharge [m^3/s],label\n0,1.5,3\n0.5,2.25,4\n");
  EXPECT_THROW(csv.append({1.0}), suite::LibraryError);
}

TEST(CsvSeries, ResumeDropsRowsAfterTheRestartTime) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm());
  const std::vector<suite::io::CsvColumn> cols{{"time", "s"}, {"q", "m^3/s"}};
  {
    suite::io::CsvSeries csv(dir / "q.csv", cols);
    for (int i = 0; i < 5; ++i) csv.append({double(i), 10.0 * i});
  }
  auto resumed = suite::io::CsvSeries::resume_at(dir / "q.csv", cols, 2.0);
  resumed.append({3.0, 31.0});
  EXPECT_EQ(read(dir / "q.csv"), "time [s],q [m^3/s]\n0,0\n1,10\n2,20\n3,31\n");
  const std::string msg = suite::testing::input_error_of([&] {
    suite::io::CsvSeries::resume_at(dir / "q.csv", {{"time", "h"}, {"q", "m^3/s"}}, 1.0);
  });
  EXPECT_NE(msg.find("differs from 'time [h],q [m^3/s]'"), std::string::npos) << msg;
}

TEST(CsvSeries, ResumeKeepsTheRowAtTheRestartTimeWhateverItsRounding) {
  // 3 * 0.3 = 0.8999999999999999 in binary; printed with 12 digits it reads back as 0.9,
  // which is larger. The row written at the restart time must survive the resume.
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm());
  const std::vector<suite::io::CsvColumn> cols{{"time", "s"}};
  {
    suite::io::CsvSeries csv(dir / "t.csv", cols);
    for (int i = 0; i <= 5; ++i) csv.append({i * 0.3});
  }
  ASSERT_LT(3 * 0.3, 0.9);
  suite::io::CsvSeries::resume_at(dir / "t.csv", cols, 3 * 0.3);
  EXPECT_EQ(read(dir / "t.csv"), "time [s]\n0\n0.3\n0.6\n0.9\n");
}

}  // namespace
