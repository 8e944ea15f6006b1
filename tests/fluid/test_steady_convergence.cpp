// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app's stopping rule of one steady solve (fluid-app/coupling/steadyConvergence.H),
// without OpenFOAM: residual drop, minimum and stable iterations, and the force-error estimate
// on exact geometric sequences (where the estimate equals the true remaining error).
#include "steadyConvergence.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using fsi::fluid::SolveControls;
using fsi::fluid::SteadyConvergence;

namespace
{
const double kNoForce[3] = {0, 0, 0};

// First iteration (1-based) at which the rule says stop, feeding residuals r(k) and a force
// F(k) along x; 0 when it never stops within `cap` iterations.
template <class Residual, class Force>
int stopIteration(const SolveControls& c, double tolU, double tolP, Residual r, Force f,
                  int cap = 200)
{
    SteadyConvergence rule(c, tolU, tolP);
    for (int k = 1; k <= cap; ++k)
    {
        const double force[3] = {f(k), 0, 0};
        if (rule.update(k, r(k), r(k), force))
            return k;
    }
    return 0;
}
} // namespace

TEST(SteadyConvergence, ResidualDropStopsAtTheFirstIterationBelowIt)
{
    SolveControls c;
    c.residualDrop = 1e-2;
    // r_k = 0.5^(k-1): r_k <= 1e-2 r_1 first at k = 8 (0.5^7 = 0.0078)
    const int k = stopIteration(
        c, 0, 0, [](int k) { return std::pow(0.5, k - 1); }, [](int) { return 0.0; });
    EXPECT_EQ(k, 8);
}

TEST(SteadyConvergence, AbsoluteResidualControlAlsoStops)
{
    SolveControls c; // no drop: fvSolution's residualControl decides
    const int k = stopIteration(
        c, 1.5e-3, 1.5e-3, [](int k) { return std::pow(0.1, k); }, [](int) { return 0.0; });
    EXPECT_EQ(k, 3);
}

TEST(SteadyConvergence, NeverBeforeMinIterations)
{
    SolveControls c;
    c.residualDrop = 0.5;
    c.minIterations = 12;
    const int k = stopIteration(
        c, 0, 0, [](int k) { return std::pow(0.1, k); }, [](int) { return 0.0; });
    EXPECT_EQ(k, 12);
}

TEST(SteadyConvergence, EstimateIsExactOnAGeometricSequence)
{
    // changes c q^j: rho = q, error = last change * q / (1 - q)
    const double q = 0.5;
    std::vector<double> changes;
    for (int j = 0; j < 6; ++j)
        changes.push_back(3.0 * std::pow(q, j));
    EXPECT_NEAR(SteadyConvergence::estimatedForceError(changes), changes.back() * q / (1 - q),
                1e-14 * changes.back());
}

TEST(SteadyConvergence, EstimateAssumesRho09UntilFourChangesAndClipsAt098)
{
    EXPECT_NEAR(SteadyConvergence::estimatedForceError({2.0, 1.0, 0.5}), 0.5 * 9.0, 1e-14);
    // growing changes: rho clipped to 0.98, error = 49 * last change
    EXPECT_NEAR(SteadyConvergence::estimatedForceError({1.0, 2.0, 4.0, 8.0}), 8.0 * 49.0, 1e-12);
}

TEST(SteadyConvergence, ForceErrorCriterionStopsWhenTheTrueErrorMeetsTheTolerance)
{
    // F_k = F* + a q^k: the estimate is the true error a q^k from the fourth change on (k >= 5).
    // a q^k <= tol |F_k| with F* = 10, a = 1, q = 0.5, tol = 1e-3: first at k = 7.
    SolveControls c;
    c.forceTolerance = 1e-3;
    c.residualRequired = false;
    c.estimateError = true;
    const int k = stopIteration(
        c, 0, 0, [](int) { return 1.0; }, [](int k) { return 10.0 + std::pow(0.5, k); });
    EXPECT_EQ(k, 7);
}

TEST(SteadyConvergence, ResidualsAndForceMustBothHold)
{
    SolveControls c;
    c.residualDrop = 1e-6; // residuals reach it only at k = 21
    c.forceTolerance = 1e-3;
    const int k = stopIteration(
        c, 0, 0, [](int k) { return std::pow(0.5, k - 1); },
        [](int k) { return 10.0 + std::pow(0.5, k); });
    EXPECT_EQ(k, 21);
}

TEST(SteadyConvergence, StableIterationsIgnoreAPauseOfAnOscillatingForce)
{
    // Per-iteration change test (fsiDict controls): the force pauses at iterations 4-5 (two
    // zero changes), then moves again, and settles from iteration 8 on.
    const std::vector<double> F = {0, 1.0, 2.0, 3.0, 3.0, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0, 5.0, 5.0};
    SolveControls c;
    c.forceTolerance = 1e-6;
    c.residualRequired = false;
    auto force = [&](int k) { return F[std::size_t(k)]; };
    auto one = [](int) { return 1.0; };
    EXPECT_EQ(stopIteration(c, 0, 0, one, force, 12), 4); // stableIterations 1: the pause
    c.stableIterations = 3;
    EXPECT_EQ(stopIteration(c, 0, 0, one, force, 12), 10); // changes 0 at 8, 9, 10
}

TEST(SteadyConvergence, NoForceCriterionIgnoresTheForce)
{
    SolveControls c;
    c.residualDrop = 0.1;
    SteadyConvergence rule(c, 0, 0);
    EXPECT_FALSE(rule.update(1, 1.0, 1.0, kNoForce));
    EXPECT_TRUE(rule.update(2, 0.05, 0.05, kNoForce));
}

// A damped oscillation F_k = F* + A d^k cos(pi k / 10) (period 20 iterations): the change
// passes through zero at every turning point, and so does the geometric estimate, which stops
// there with the true error near the amplitude. oscillationWindow 20 (a period: a half-period
// window can miss the reversal, since damping moves the turning points) keeps the solve going
// until half the window's range, and with it the true error, is below the tolerance.
TEST(SteadyConvergence, OscillationWindowDoesNotStopAtATurningPoint)
{
    const double target = 10.0, amplitude = 0.05, damping = 0.93, tol = 5e-5;
    auto force = [&](int k)
    { return target + amplitude * std::pow(damping, k) * std::cos(M_PI * k / 10.0); };
    auto one = [](int) { return 1.0; };
    SolveControls c;
    c.forceTolerance = tol;
    c.residualRequired = false;
    c.estimateError = true;
    const int early = stopIteration(c, 0, 0, one, force, 400);
    ASSERT_GT(early, 0);
    const double earlyError = std::abs(force(early) - target) / target;
    EXPECT_GT(earlyError, 10 * tol) << "stopped at " << early; // fooled by a turning point

    c.oscillationWindow = 20;
    const int late = stopIteration(c, 0, 0, one, force, 400);
    ASSERT_GT(late, early);
    EXPECT_LE(std::abs(force(late) - target) / target, tol) << "stopped at " << late;
    // and not much later than needed: the envelope A d^k meets tol |F*| at k0
    const double k0 = std::log(tol * target / amplitude) / std::log(damping);
    EXPECT_LT(late, k0 + 20);
    c.oscillationWindow = 10; // half a period: can miss the reversal (printed, not asserted)
    const int half = stopIteration(c, 0, 0, one, force, 400);
    std::printf("damped oscillation, tolerance %.0e: stop at %d (error %.1e) without a window, "
                "%d (%.1e) with window 10, %d (%.1e) with window 20\n",
                tol, early, earlyError, half, std::abs(force(half) - target) / target, late,
                std::abs(force(late) - target) / target);
}

// A monotone (geometric) convergence has no sign reversal: the window changes nothing.
TEST(SteadyConvergence, OscillationWindowLeavesMonotoneConvergenceAlone)
{
    SolveControls c;
    c.forceTolerance = 1e-3;
    c.residualRequired = false;
    c.estimateError = true;
    c.oscillationWindow = 8;
    const int k = stopIteration(
        c, 0, 0, [](int) { return 1.0; }, [](int k) { return 10.0 + std::pow(0.5, k); });
    EXPECT_EQ(k, 7);
    const std::vector<double> rising = {1, 0, 0, 2, 0, 0, 2.5, 0, 0, 2.6, 0, 0};
    EXPECT_EQ(SteadyConvergence::oscillationBand(rising), 0.0);
    const std::vector<double> turning = {1, 0, 0, 2, 0, 0, 1.5, 0, 0};
    EXPECT_DOUBLE_EQ(SteadyConvergence::oscillationBand(turning), 0.5);
}
