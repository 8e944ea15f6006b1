// SPDX-License-Identifier: GPL-3.0-or-later
// The Anderson mixing of fluid-app's SIMPLE acceleration (fluid-app/acceleration/andersonMixer.H),
// without OpenFOAM, on linear fixed-point maps G(x) = A x + b whose exact fixed point is known:
// with depth >= the dimension, Anderson mixing is GMRES on (I - A) x = b and reaches the fixed
// point after dimension + 1 sweeps; the plain iteration contracts by the spectral radius only.
#include "andersonMixer.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using fsi::fluid::AndersonMixer;

namespace
{
constexpr int kDim = 6;

// A = Q diag(lambda) Q^T with a fixed orthogonal-ish Q (Householder of v), eigenvalues up to 0.95:
// the plain iteration needs ~450 sweeps for 1e-10.
struct LinearMap
{
    std::vector<double> a, b, fixedPoint;
    LinearMap()
    {
        const double lambda[kDim] = {0.95, -0.6, 0.8, 0.3, -0.9, 0.5};
        double v[kDim] = {1, -2, 0.5, 3, -1, 2};
        double vv = 0;
        for (double x : v)
            vv += x * x;
        a.assign(kDim * kDim, 0.0);
        for (int i = 0; i < kDim; ++i)
            for (int j = 0; j < kDim; ++j)
                for (int k = 0; k < kDim; ++k)
                {
                    const double qik = (i == k) - 2 * v[i] * v[k] / vv;
                    const double qjk = (j == k) - 2 * v[j] * v[k] / vv;
                    a[i * kDim + j] += qik * lambda[k] * qjk;
                }
        fixedPoint = {1.0, -0.5, 2.0, 0.25, -1.5, 0.75};
        b.resize(kDim); // b = (I - A) x*
        for (int i = 0; i < kDim; ++i)
        {
            b[i] = fixedPoint[i];
            for (int j = 0; j < kDim; ++j)
                b[i] -= a[i * kDim + j] * fixedPoint[j];
        }
    }
    std::vector<double> operator()(const std::vector<double>& x) const
    {
        std::vector<double> g(b);
        for (int i = 0; i < kDim; ++i)
            for (int j = 0; j < kDim; ++j)
                g[i] += a[i * kDim + j] * x[j];
        return g;
    }
    double error(const std::vector<double>& x) const
    {
        double e = 0;
        for (int i = 0; i < kDim; ++i)
            e = std::max(e, std::abs(x[i] - fixedPoint[i]));
        return e;
    }
};

const AndersonMixer::SumAcrossRanks kOneRank = [](std::vector<double>&) {};

// Sweeps of G from x = 0 with the mixer (depth), returns the error after `sweeps`.
double errorAfter(int sweeps, int depth, double maxCoefficientSum = 1e6, int* restarts = nullptr)
{
    const LinearMap G;
    AndersonMixer mixer(depth, maxCoefficientSum);
    std::vector<double> x(kDim, 0.0);
    for (int k = 0; k < sweeps; ++k)
    {
        std::vector<double> g = G(x);
        std::vector<double> f(kDim);
        for (int i = 0; i < kDim; ++i)
            f[i] = g[i] - x[i];
        const AndersonMixer::Step step = mixer.mix(g, f, kOneRank);
        if (restarts && step.restarted)
            ++*restarts;
        x = g;
    }
    return G.error(x);
}

double plainErrorAfter(int sweeps)
{
    const LinearMap G;
    std::vector<double> x(kDim, 0.0);
    for (int k = 0; k < sweeps; ++k)
        x = G(x);
    return G.error(x);
}
} // namespace

TEST(AndersonMixer, DepthAtLeastTheDimensionIsExactAfterDimensionPlusOneSweeps)
{
    // GMRES equivalence: the fixed point to rounding after kDim + 1 sweeps (+1: the first sweep
    // has no difference to mix), where the plain iteration is still far off
    EXPECT_LT(errorAfter(kDim + 2, kDim), 1e-9);
    EXPECT_GT(plainErrorAfter(kDim + 2), 1e-2);
}

TEST(AndersonMixer, ShallowDepthStillBeatsThePlainIteration)
{
    // depth 2 on the same map (measured: 1.9e-5 after 60 sweeps against the plain iteration's
    // 1.2e-2): more than a hundred times closer to the fixed point
    const double mixed = errorAfter(60, 2), plain = plainErrorAfter(60);
    EXPECT_LT(mixed, 1e-4);
    EXPECT_LT(mixed, 1e-2 * plain);
}

TEST(AndersonMixer, WildCoefficientsRestartToThePlainSweep)
{
    // a bound below any useful mix: every mix is refused and x follows the plain iteration
    int restarts = 0;
    const double e = errorAfter(20, kDim, 1e-9, &restarts);
    EXPECT_NEAR(e, plainErrorAfter(20), 1e-14);
    EXPECT_GT(restarts, 0);
}

TEST(AndersonMixer, ResetForgetsTheHistoryAndSizesAreChecked)
{
    AndersonMixer mixer(3, 20);
    std::vector<double> g = {1, 2}, f = {0.1, 0.2};
    EXPECT_EQ(mixer.mix(g, f, kOneRank).columns, 0); // first sweep: nothing to mix
    std::vector<double> g3 = {1, 2, 3}, f3 = {0.1, 0.2, 0.3};
    EXPECT_THROW(mixer.mix(g3, f3, kOneRank), std::invalid_argument);
    mixer.reset();
    EXPECT_EQ(mixer.mix(g3, f3, kOneRank).columns, 0); // a new history may change size
    EXPECT_THROW(AndersonMixer(0, 20), std::invalid_argument);
    EXPECT_THROW(AndersonMixer(3, 0), std::invalid_argument);
}
