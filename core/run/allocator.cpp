#include "core/run/allocator.hpp"

#include <malloc.h>

namespace suite {

void keep_freed_memory_for_reuse() {
  // 32 MiB is glibc's largest mmap threshold on 64-bit systems; setting it also stops glibc's
  // own threshold from moving.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

}  // namespace suite
