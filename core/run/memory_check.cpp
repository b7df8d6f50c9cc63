#include "core/run/memory_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "core/errors.hpp"

namespace suite {

namespace {

std::optional<double> read_number(const std::string& file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// MemAvailable of /proc/meminfo, bytes.
std::optional<double> mem_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return std::nullopt;
}

// The headroom of this process's memory control group, bytes (v2, else v1).
std::optional<double> cgroup_headroom() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    // "0::/path" (v2) or "N:memory:/path" (v1; the controller list may name several)
    const auto a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (controllers.empty()) {
      const std::string dir = "/sys/fs/cgroup" + path;
      const auto limit = read_number(dir + "/memory.max"), used = read_number(dir + "/memory.current");
      if (limit && used) return *limit - *used;
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      const std::string dir = "/sys/fs/cgroup/memory" + path;
      const auto limit = read_number(dir + "/memory.limit_in_bytes"),
                 used = read_number(dir + "/memory.usage_in_bytes");
      // v1 reports "no limit" as a huge number (about 2^63 rounded to pages).
      if (limit && used && *limit < 1e18) return *limit - *used;
    }
  }
  return std::nullopt;
}

}  // namespace

AvailableMemory available_memory() {
  AvailableMemory m{std::numeric_limits<double>::infinity(), "unknown"};
  if (const auto a = mem_available()) m = {*a, "MemAvailable"};
  if (const auto c = cgroup_headroom(); c && *c < m.bytes) m = {*c, "the control group's memory limit"};
  return m;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int i = 0;
  while (bytes >= 1024.0 && i < 6) bytes /= 1024.0, ++i;
  return fmt::format("{:.3g} {}", bytes, units[i]);
}

void require_memory(const mpi::Comm& comm, double total_bytes, const std::string& what, const std::string& breakdown,
                    const std::string& fix) {
  const mpi::Comm node = comm.split_shared();
  const auto available = available_memory();
  const double need = total_bytes / comm.size() * node.size();
  // The node short of memory by the largest factor speaks for all (the same message on every rank).
  const double ratio = std::isfinite(available.bytes) ? need / std::max(available.bytes, 1.0) : 0.0;
  const double worst = comm.max(ratio);
  if (worst <= 1.0) return;
  std::string message = ratio == worst ? fmt::format(
                                             "{} needs about {} ({}) on a node running {} of its {} ranks, and "
                                             "{} is available there ({}); {}",
                                             what, format_bytes(need), breakdown, node.size(), comm.size(),
                                             format_bytes(available.bytes), available.source, fix)
                                       : std::string();
  // The lowest rank holding the message sends it.
  const long long sender =
      -comm.max(message.empty() ? -static_cast<long long>(comm.size()) : -static_cast<long long>(comm.rank()));
  comm.broadcast(message, static_cast<int>(sender));
  throw InputError(message);
}

}  // namespace suite
