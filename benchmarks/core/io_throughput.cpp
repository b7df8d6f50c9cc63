// Output cost of the core library on this machine: one collective HDF5 output step (particle
// arrays: position and velocity rows x 3, mass; 56 bytes a particle) and one checkpoint of the
// same data (written, fsynced, renamed), for a range of particle counts per rank.
//
//   mpiexec -n N io_throughput [--out FILE.csv] [--repeats R] [--dir SCRATCH]
//
// Prints, for each size, the median over R repeats of the slowest rank's wall time and the
// resulting bandwidth, and writes them to FILE.csv with the machine, build and git hash.
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/checkpoint/checkpoint.hpp"
#include "core/io/h5_file.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/build_info.hpp"

namespace {

using clock_type = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Slowest rank's wall time of f(), all ranks starting together.
template <class F>
double timed(const suite::mpi::Comm& comm, F&& f) {
  comm.barrier();
  const auto t0 = clock_type::now();
  f();
  return comm.max(std::chrono::duration<double>(clock_type::now() - t0).count());
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm comm(MPI_COMM_WORLD);
  std::string out_csv, dir = std::filesystem::temp_directory_path() / "suite-io-bench";
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--out") out_csv = argv[i + 1];
    if (a == "--repeats") repeats = std::stoi(argv[i + 1]);
    if (a == "--dir") dir = argv[i + 1];
  }
  if (comm.is_root()) std::filesystem::create_directories(dir);
  comm.barrier();

  const auto b = suite::build_info();
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  std::ofstream csv;
  if (comm.is_root()) {
    std::printf("%-14s %-14s %-12s %-12s %-12s %-12s\n", "particles/rank", "bytes total", "step [s]", "step [MB/s]",
                "ckpt [s]", "ckpt [MB/s]");
    if (!out_csv.empty()) {
      csv.open(out_csv);
      csv << "# io_throughput: host " << host << ", " << sysconf(_SC_NPROCESSORS_ONLN) << " cores, " << comm.size()
          << " ranks, suite " << b.version << " (" << b.git_hash << "), " << b.build_type << ", " << b.compiler
          << ", medians of " << repeats << " repeats\n";
      csv << "ranks,particles_per_rank,bytes_total,step_s,step_MBps,checkpoint_s,checkpoint_MBps\n";
    }
  }
  for (long long n : {1'000LL, 10'000LL, 100'000LL, 1'000'000LL, 4'000'000LL}) {
    std::vector<double> pos(static_cast<std::size_t>(3 * n)), vel(pos.size()), mass(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = 1e-3 * double(i) + comm.rank(), vel[i] = -pos[i];
    for (std::size_t i = 0; i < mass.size(); ++i) mass[i] = 1.0 + 1e-6 * double(i);
    const double bytes = double(comm.size()) * double(n) * 7.0 * sizeof(double);
    std::vector<double> step_s, ckpt_s;
    for (int r = 0; r < repeats; ++r) {
      step_s.push_back(timed(comm, [&] {
        suite::io::H5File f(comm, std::filesystem::path(dir) / "step.h5", suite::io::H5File::Mode::create);
        f.write_rows<double>("/particles/position", pos, 3);
        f.write_rows<double>("/particles/velocity", vel, 3);
        f.write_rows<double>("/particles/mass", mass);
      }));
      ckpt_s.push_back(timed(comm, [&] {
        suite::checkpoint::Writer w(comm, std::filesystem::path(dir) / "checkpoint_000000001.h5",
                                    {"io_throughput", 1, 1, 0.0, "", 0});
        w.write<double>("position", pos);
        w.write<double>("velocity", vel);
        w.write<double>("mass", mass);
        w.commit();
      }));
    }
    const double s = median(step_s), c = median(ckpt_s);
    if (comm.is_root()) {
      std::printf("%-14lld %-14.3g %-12.4g %-12.1f %-12.4g %-12.1f\n", n, bytes, s, bytes / s / 1e6, c,
                  bytes / c / 1e6);
      if (csv)
        csv << comm.size() << ',' << n << ',' << bytes << ',' << s << ',' << bytes / s / 1e6 << ',' << c << ','
            << bytes / c / 1e6 << '\n';
    }
  }
  if (comm.is_root()) std::filesystem::remove_all(dir);
  return 0;
}
