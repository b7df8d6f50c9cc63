#pragma once
// The process's allocator policy for programs that allocate and free the same large buffers over
// and over (seedcarve: 36 decoded views, their HSV copies and masks per seed).

namespace suite {

// Large blocks (up to 32 MiB) come from the heap and freed memory stays with the process (up to
// 256 MiB) instead of going back to the kernel after each seed, so the next seed's buffers reuse
// mapped pages rather than fault in fresh ones: glibc by default maps each block over 128 KiB to
// itself and unmaps it on free. On the 2-core VM the benchmarks run on, page faults took three
// quarters of seedcarve's segmentation (docs/carving.md, "Throughput"). Call it first in main.
void keep_freed_memory_for_reuse();

}  // namespace suite
