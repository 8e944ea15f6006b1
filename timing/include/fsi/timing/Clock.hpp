// SPDX-License-Identifier: GPL-3.0-or-later
// Clocks for cost figures (benchmarks, solid-app's summary): seconds, as double.
// Header only (CMake target fsi_timing). Thread-safe; no MPI.
#pragma once

#include <chrono>
#include <ctime>

namespace fsi
{
namespace timing
{

// CPU seconds (user + system, summed over every thread) this process has used since it
// started. A process that waits by polling (MPI busy-wait) counts its waiting here too.
inline double processCpuSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Monotonic wall-clock seconds from an arbitrary origin: only differences have a meaning.
inline double wallSeconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

} // namespace timing
} // namespace fsi
