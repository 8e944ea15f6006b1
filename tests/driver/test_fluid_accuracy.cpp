// SPDX-License-Identifier: GPL-3.0-or-later
// The forcing term of the inexact fluid solves (FluidAccuracy.hpp), the progress clock and the
// coupling log's CSV quoting.
#include "driver/CouplingLog.hpp"
#include "driver/FluidAccuracy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace fsi::driver;

TEST(ForcingTerm, WithoutTheBlockTheFluidKeepsItsOwnControls)
{
    const ForcingTerm f(nullptr);
    EXPECT_FALSE(f.driverControlled());
    const auto a = f.forIterate(1e-3, 1e-3);
    EXPECT_FALSE(a.driverControlled);
    EXPECT_TRUE(a.isFinal);
}

TEST(ForcingTerm, AccuracyFollowsTheInterfaceResidualWithinItsBounds)
{
    FluidAccuracyParameters p;
    p.finalForceTolerance = 2e-4;
    p.maxForceTolerance = 1e-2;
    p.forcingFactor = 0.1;
    p.minIterations = 3;
    p.finalResidualDrop = 1e-2;
    const ForcingTerm f(&p);
    // eta = 0.1 * 1e-4 / 5e-3 = 2e-3: a loose solve, no residual drop asked
    const auto loose = f.forIterate(1e-4, 5e-3);
    EXPECT_TRUE(loose.driverControlled);
    EXPECT_FALSE(loose.isFinal);
    EXPECT_NEAR(loose.forceTolerance, 2e-3, 1e-15);
    EXPECT_EQ(loose.residualDrop, 0.0);
    EXPECT_EQ(loose.minIterations, 3);
    // a large residual: the loosest; unknown residual or zero displacement: the loosest
    EXPECT_DOUBLE_EQ(f.forIterate(1.0, 5e-3).forceTolerance, 1e-2);
    EXPECT_DOUBLE_EQ(f.forIterate(-1.0, 5e-3).forceTolerance, 1e-2);
    EXPECT_DOUBLE_EQ(f.forIterate(std::nan(""), 5e-3).forceTolerance, 1e-2);
    EXPECT_DOUBLE_EQ(f.forIterate(1e-4, 0.0).forceTolerance, 1e-2);
    // a small residual: the final accuracy, with its residual drop
    const auto tight = f.forIterate(1e-7, 5e-3);
    EXPECT_TRUE(tight.isFinal);
    EXPECT_DOUBLE_EQ(tight.forceTolerance, 2e-4);
    EXPECT_DOUBLE_EQ(tight.residualDrop, 1e-2);
    EXPECT_TRUE(f.finalAccuracy().isFinal);
    EXPECT_DOUBLE_EQ(f.finalAccuracy().forceTolerance, 2e-4);
}

TEST(ForcingTerm, InvalidParametersNameTheKey)
{
    FluidAccuracyParameters p;
    p.maxForceTolerance = 1e-5; // below the final 2e-4
    try
    {
        ForcingTerm f(&p);
        FAIL() << "max below final accepted";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("coupling.fluid_accuracy.max_force_tolerance"),
                  std::string::npos)
            << e.what();
    }
}

// Constant steps and constant cost per level: the estimate is the simulated time to go times
// the cost per simulated second, exactly.
TEST(ProgressClock, ConstantStepsGiveTheCostPerSimulatedSecond)
{
    ProgressClock clock(3);
    clock.levelDone(0.0, 0.0, 5.0);
    EXPECT_LT(clock.remaining(100.0, 0.0), 0.0); // unknown before a level with dt > 0
    for (int k = 1; k <= 5; ++k)
        clock.levelDone(2.0 * k, 2.0, 5.0 + 3.0 * k); // 3 s per level of 2 s
    EXPECT_NEAR(clock.remaining(100.0, 0.0), 1.5 * 90.0, 1e-9);
    EXPECT_DOUBLE_EQ(clock.remaining(10.0, 0.0), 0.0);
}

// Steps doubling each level at a constant cost per level: the levels left are counted with the
// growth (capped by max_step), not the early cost per simulated second (which would say 50x
// more here).
TEST(ProgressClock, GrowingStepsCountTheLevelsLeft)
{
    ProgressClock clock(3);
    clock.levelDone(0.0, 0.0, 0.0);
    double t = 0.0, dt = 1.0;
    for (int k = 1; k <= 4; ++k, dt *= 2) // t = 1, 3, 7, 15 after steps 1, 2, 4, 8
    {
        t += dt;
        clock.levelDone(t, dt, 10.0 * k);
    }
    // next steps 16, 32, 64 (-> 127), then capped at 100: 227, 327, 427 >= 400: 6 levels
    EXPECT_NEAR(clock.remaining(400.0, 100.0), 6 * 10.0, 1e-9);
    // unlimited: 16, 32, 64, 128, 256 (-> 511): 5 levels
    EXPECT_NEAR(clock.remaining(400.0, 0.0), 5 * 10.0, 1e-9);
}

// coupling.csv's note column is free text ("clamped to 1 (min_relaxation 0.001, max_relaxation
// 1)"): quoted so that every row keeps the header's column count.
TEST(CouplingLog, NotesAreQuotedCsvFields)
{
    EXPECT_EQ(fsi::driver::csvField("plain note"), "plain note");
    EXPECT_EQ(fsi::driver::csvField(""), "");
    EXPECT_EQ(fsi::driver::csvField("a, b"), "\"a, b\"");
    EXPECT_EQ(fsi::driver::csvField("say \"x\""), "\"say \"\"x\"\"\"");
}
