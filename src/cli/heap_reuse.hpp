// The heap policy of the commands that fit a log (identify, diagnose): they allocate and free
// many sample-sized matrices (tens of MB each). glibc serves such blocks by mmap and unmaps them
// on free, so every new one page-faults its memory in afresh; kept on the heap instead, a freed
// block's pages serve the next one (on an hour of log: diagnose's page faults 701 k → 582 k).
#pragma once

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tpf::cli {

/// Every block from the heap (no mmap per block), and no heap trimming: freed memory stays mapped
/// for the next allocation; the process returns it at exit. Results do not change.
/// Elsewhere than glibc: nothing.
inline void reuse_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
#endif
}

}  // namespace tpf::cli
