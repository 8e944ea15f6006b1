// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Convergence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace fsi::acceleration;

TEST(Convergence, MeasuresThePapersCriterionAndTheRelativeOne)
{
    // r = (3, 4): |r| = 5, |r|/sqrt(2) = 3.5355; |u_hat| = |(4, 4)| = 5.657.
    const Eigen::Vector2d previous(1.0, 0.0), output(4.0, 4.0);
    ConvergenceParameters p;
    p.absoluteTolerance = 3.6;
    ConvergenceMeasure m = measureConvergence(previous, output, p);
    EXPECT_DOUBLE_EQ(m.rmsResidual, 5.0 / std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(m.relativeResidual, 5.0 / std::sqrt(32.0));
    EXPECT_TRUE(m.converged);
    p.relativeTolerance = 0.8; // both active: 0.884 >= 0.8 fails
    EXPECT_FALSE(measureConvergence(previous, output, p).converged);
    p.absoluteTolerance = 0.0;
    p.relativeTolerance = 0.9;
    EXPECT_TRUE(measureConvergence(previous, output, p).converged);
    EXPECT_EQ(measureConvergence(previous, output, p).toString(),
              "|r|/sqrt(n) 3.536e+00 |r|/|u| 8.839e-01 converged");

    const Eigen::Vector2d bad(std::nan(""), 0.0);
    m = measureConvergence(previous, bad, p);
    EXPECT_FALSE(m.finite);
    EXPECT_FALSE(m.converged);
}

TEST(Convergence, NeedsOneTolerance)
{
    ConvergenceParameters p;
    EXPECT_THROW(p.validate(), std::runtime_error);
    p.absoluteTolerance = 1e-8;
    EXPECT_NO_THROW(p.validate());
    p.relativeTolerance = -1.0;
    EXPECT_THROW(p.validate(), std::runtime_error);
}

// A flow accepted in the mean with relative band b: the tolerances widen to band_factor b
// (relative) and band_factor b rms(u_hat) (absolute), never below the configured ones; a steady
// flow (b = 0) and band_factor 0 leave them alone.
TEST(Convergence, WidensTheTolerancesToAFlowsBand)
{
    ConvergenceParameters p;
    p.absoluteTolerance = 5e-6;
    p.relativeTolerance = 1e-4;
    p.bandFactor = 2.0;
    auto w = p.widenedForBand(1e-3, 9e-3); // band +-0.1 %, rms(u_hat) 9 mm
    EXPECT_DOUBLE_EQ(w.absoluteTolerance, 1.8e-5);
    EXPECT_DOUBLE_EQ(w.relativeTolerance, 2e-3);
    EXPECT_NE(w.describe().find("|r|/sqrt(n) < "), std::string::npos) << w.describe();
    EXPECT_NE(w.describe().find(", |r|/|u| < "), std::string::npos) << w.describe();
    w = p.widenedForBand(1e-3, 1e-3); // 2e-6 m < 5e-6 m: stays
    EXPECT_DOUBLE_EQ(w.absoluteTolerance, 5e-6);
    EXPECT_DOUBLE_EQ(p.widenedForBand(0.0, 9e-3).absoluteTolerance, 5e-6);
    EXPECT_DOUBLE_EQ(p.widenedForBand(0.0, 9e-3).relativeTolerance, 1e-4);
    p.relativeTolerance = 0.0; // an inactive criterion stays inactive
    EXPECT_DOUBLE_EQ(p.widenedForBand(1e-3, 9e-3).relativeTolerance, 0.0);
    p.bandFactor = 0.0;
    EXPECT_DOUBLE_EQ(p.widenedForBand(1e-3, 9e-3).absoluteTolerance, 5e-6);
    p.bandFactor = -1.0;
    EXPECT_THROW(p.validate(), std::runtime_error);
}
