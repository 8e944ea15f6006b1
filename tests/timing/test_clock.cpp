// SPDX-License-Identifier: GPL-3.0-or-later
// fsi::timing clocks: properties that hold on any machine, loaded or not (no timed thresholds
// beyond a 10 s safety bound).
#include "fsi/timing/Clock.hpp"

#include <gtest/gtest.h>

namespace
{
using fsi::timing::processCpuSeconds;
using fsi::timing::wallSeconds;

// Busy work until this process has used `cpuSeconds` of CPU, or 10 s of wall time have passed.
// Returns {CPU used, wall elapsed}.
std::pair<double, double> spin(double cpuSeconds)
{
    const double cpu0 = processCpuSeconds(), wall0 = wallSeconds();
    volatile double sink = 0.0;
    while (processCpuSeconds() - cpu0 < cpuSeconds && wallSeconds() - wall0 < 10.0)
        for (int i = 0; i < 10000; ++i)
            sink = sink + 1e-9 * i;
    return {processCpuSeconds() - cpu0, wallSeconds() - wall0};
}
} // namespace

TEST(Clock, ProcessCpuAdvancesUnderWork)
{
    const auto [cpu, wall] = spin(0.05);
    EXPECT_GE(cpu, 0.05); // reached before the 10 s bound: the CPU clock runs
    EXPECT_LT(wall, 10.0);
}

TEST(Clock, OneThreadUsesNoMoreCpuThanWallTime)
{
    const auto [cpu, wall] = spin(0.05);
    // a single-threaded process: CPU time <= elapsed wall time (1 ms for clock granularity)
    EXPECT_LE(cpu, wall + 1e-3);
}

TEST(Clock, WallClockIsMonotonic)
{
    double previous = wallSeconds();
    for (int i = 0; i < 100000; ++i)
    {
        const double now = wallSeconds();
        ASSERT_GE(now, previous);
        previous = now;
    }
}
