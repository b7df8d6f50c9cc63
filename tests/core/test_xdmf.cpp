// Writes a two-step particle + grid-cell series; tests/core/check_xdmf.py then parses the
// .xmf with a real XML parser and opens every dataset it references with h5py.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/io/h5_file.hpp"
#include "core/io/xdmf.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::io::XdmfArray;
using suite::io::XdmfGrid;

std::vector<XdmfGrid> write_step(const suite::mpi::Comm& comm, const std::filesystem::path& dir, int step) {
  const std::string name = "step_" + std::to_string(step) + ".h5";
  suite::io::H5File f(comm, dir / name, suite::io::H5File::Mode::create);
  // Particles: 4 per rank on a line; one quad cell per rank for the grid.
  std::vector<double> pos, vel, corners;
  for (int i = 0; i < 4; ++i) {
    pos.insert(pos.end(), {comm.rank() + 0.25 * i, 0.1 * step, 0.0});
    vel.insert(vel.end(), {1.0, 0.0, -0.5});
  }
  const double x0 = comm.rank();
  corners = {x0, 0, x0 + 1, 0, x0 + 1, 1, x0, 1};
  auto p = f.write_rows<double>("/particles/position", pos, 3);
  f.write_rows<double>("/particles/velocity", vel, 3);
  auto nodes = f.write_rows<double>("/grid/xy", corners, 2);
  std::vector<long long> quad;
  for (long long k = 0; k < 4; ++k) quad.push_back(nodes.offset + k);
  auto cells = f.write_rows<long long>("/grid/quads", quad, 4);
  std::vector<double> mass{1.0 + comm.rank()};
  f.write_rows<double>("/grid/mass", mass);

  XdmfGrid particles{"particles",
                     name,
                     suite::io::XdmfTopology::polyvertex,
                     {"position", "/particles/position", p.total, 3},
                     {},
                     {{"velocity", "/particles/velocity", p.total, 3}},
                     {}};
  XdmfGrid grid{"grid",
                name,
                suite::io::XdmfTopology::quadrilateral,
                {"xy", "/grid/xy", nodes.total, 2},
                {"quads", "/grid/quads", cells.total, 4, "Int", 8},
                {},
                {{"mass", "/grid/mass", cells.total, 1}}};
  return {particles, grid};
}

TEST(Xdmf, TimeSeriesReferencesEveryDatasetAndResumes) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  suite::io::XdmfSeries series(dir / "series.xmf");
  std::vector<XdmfGrid> last;
  for (int step = 0; step < 3; ++step) {
    last = write_step(comm, dir, step);
    if (comm.is_root()) series.add_step(0.5 * step, last);
  }
  if (comm.is_root()) {
    // A restart from t = 0.5 drops the step at t = 1.0; the rerun writes it again.
    suite::io::XdmfSeries resumed(dir / "series.xmf");
    resumed.resume_at(0.5);
    EXPECT_EQ(resumed.steps(), 2u);
    resumed.add_step(1.0, last);
    EXPECT_EQ(resumed.steps(), 3u);
    std::ifstream in(dir / "series.xmf");
    std::stringstream s;
    s << in.rdbuf();
    EXPECT_NE(s.str().find("CollectionType=\"Temporal\""), std::string::npos);
    EXPECT_NE(s.str().find("step_1.h5:/particles/velocity"), std::string::npos);
  }
  // check_xdmf.py (a CTest fixture after this test) validates series.xmf against the files.
}

}  // namespace
