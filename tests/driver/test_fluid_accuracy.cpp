// SPDX-License-Identifier: GPL-3.0-or-later
// The forcing term of the inexact fluid solves (FluidAccuracy.hpp) and the progress clock.
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
        EXPECT_NE(std::string(e.what()).find("coupling.fluid_accuracy.max_force_tolerance"), std::string::npos)
            << e.what();
    }
}

// Constant cost per simulated second: the estimate is exact, however the levels are spaced.
TEST(ProgressClock, RemainingTimeFollowsTheCostPerSimulatedSecond)
{
    ProgressClock clock(3);
    EXPECT_LT(clock.remaining(100.0), 0.0); // unknown before two levels
    const double costPerSecond = 2.5;       // wall seconds per simulated second
    for (double t : {0.0, 1.0, 3.0, 7.0, 15.0})
        clock.levelDone(t, 10.0 + costPerSecond * t);
    EXPECT_NEAR(clock.remaining(100.0), costPerSecond * 85.0, 1e-9);
    EXPECT_DOUBLE_EQ(clock.remaining(15.0), 0.0);
}
