#pragma once
// A run that will not fit into memory is refused before it allocates, with one line that says
// how much it needs and how much there is, instead of ending in std::bad_alloc (or the kernel's
// OOM killer) after minutes of seeding.
//
// The memory a process may still take is the smallest of the node's MemAvailable
// (/proc/meminfo) and the headroom of its control group (cgroup v2 memory.max - memory.current,
// or v1 memory.limit_in_bytes - memory.usage_in_bytes: Slurm's --mem and --mem-per-cpu limits
// when the cluster enforces them with cgroups). The ranks of one node share it.
#include <string>

#include "core/mpi/comm.hpp"

namespace suite {

struct AvailableMemory {
  double bytes = 0;    // infinity when nothing could be read
  std::string source;  // "MemAvailable", "cgroup memory.max" or "unknown"
};

// This node's memory that processes may still take (see above). Not collective.
AvailableMemory available_memory();

// InputError on every rank if the run's `total_bytes`, spread evenly over the ranks of `comm`,
// needs more on some node than that node has available (its ranks' shares together):
//   "<what> needs about 6.3 GiB (<breakdown>) on a node running 2 of its 2 ranks, and 2.1 GiB is
//    available there (MemAvailable); <fix>"
// COLLECTIVE.
void require_memory(const mpi::Comm& comm, double total_bytes, const std::string& what, const std::string& breakdown,
                    const std::string& fix);

// Bytes as "1.2 GiB", "340 MiB", "12 KiB".
std::string format_bytes(double bytes);

}  // namespace suite
