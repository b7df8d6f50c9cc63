#pragma once
// Small helpers shared by the carving benchmarks: medians of repeated timings, command-line
// flags, and the comment line that starts every CSV (machine, date, build, git hash).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <string>
#include <vector>

#include "core/run/build_info.hpp"

namespace suite::carving::bench {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Wall-clock seconds of each of `repeats` calls of `work`, in call order.
template <class Work>
std::vector<double> time_repeats(int repeats, Work&& work) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    work();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return seconds;
}

// The value after `flag` on the command line, or `fallback` when the flag is absent.
inline std::string flag_value(int argc, char** argv, const std::string& flag, const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (argv[i] == flag) return argv[i + 1];
  return fallback;
}

// "# <program>: host H, C cores, <date>, suite V (git), build type, compiler, <what>".
inline std::string csv_header(const std::string& program, const std::string& what) {
  const auto b = suite::build_info();
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  char date[64] = {0};
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return "# " + program + ": host " + host + ", " + std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) + " cores, " + date +
         ", suite " + b.version + " (" + b.git_hash + "), " + b.build_type + ", " + b.compiler + ", " + what + "\n";
}

}  // namespace suite::carving::bench
