// SPDX-License-Identifier: GPL-3.0-or-later
// solid-app: keep large freed blocks in the heap (glibc), as fluid-app/heapSettings.H does for
// the fluid. MUMPS and the assembly allocate and free large work arrays at every factorization
// and solve; above glibc's adaptive mmap threshold each one is mapped, page-faulted in and
// unmapped again (on the coarse hydrofoil the 5 factorizations took 5.8 s with glibc's defaults,
// 3.4 s with these settings). Settings from the environment (MALLOC_MMAP_THRESHOLD_,
// MALLOC_TRIM_THRESHOLD_) win.
#pragma once

#include <cstdlib>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fsi::app
{

// Call first in main, before MPI and the solvers allocate.
inline void keepLargeBlocksInHeap()
{
#if defined(__GLIBC__)
    if (std::getenv("MALLOC_MMAP_THRESHOLD_") || std::getenv("MALLOC_TRIM_THRESHOLD_"))
        return;
    mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
#endif
}

} // namespace fsi::app
