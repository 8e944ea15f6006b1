// SPDX-License-Identifier: GPL-3.0-or-later
// inverseDistanceTree (fluid-app/meshMotion): the tree's sums against the direct sums over the
// same sources, on a foil-like set of surface points (2 000 points on the faces of a thin box
// 50 x 5 x 100 mm, areas 0.5-1.5 mm^2, a smooth bending-like translation).
//  - openingAngle 0 is the direct sum (to round-off);
//  - nearest() is the brute-force nearest source, exactly;
//  - every source closer than `near` is visited exactly;
//  - with openingAngle 0.1 / 0.2 the interpolated translation sumT / weight deviates from the
//    direct one by at most 1e-3 / 1e-2 of the largest translation (measured 3.5e-4 / 4.4e-3:
//    a margin of about 3), and halving the angle shrinks the largest deviation more than 4
//    times (measured 12: the expansion is second order, its error third order in the angle).
#include "inverseDistanceTree.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>

using namespace Foam;

namespace
{
struct Lcg
{
    std::uint64_t s = 12345;
    double next() // in [0, 1)
    {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(s >> 11) / double(1ULL << 53);
    }
};

struct Sources
{
    pointField x;
    scalarField a;
    vectorField t;
};

Sources foilLikeSources(label n)
{
    Sources s;
    s.x.setSize(n);
    s.a.setSize(n);
    s.t.setSize(n);
    Lcg r;
    const vector size(0.05, 0.005, 0.1);
    for (label i = 0; i < n; ++i)
    {
        // a point on one of the box's two large faces (y = 0 or y = 5 mm) or its rim
        point p(r.next() * size.x(), r.next() < 0.5 ? 0.0 : size.y(), r.next() * size.z());
        if (i % 10 == 0)
        {
            p.y() = r.next() * size.y();
            p.x() = r.next() < 0.5 ? 0.0 : size.x();
        }
        s.x[i] = p;
        s.a[i] = 1e-6 * (0.5 + r.next());
        const scalar z = p.z() / size.z();
        s.t[i] = vector(0.01 * z * z, 0.03 * z * z, -0.002 * z * (p.x() - 0.025) / 0.025);
    }
    return s;
}

pointField queryPoints(label n)
{
    pointField q(n);
    Lcg r;
    r.s = 777;
    for (label i = 0; i < n; ++i)
    {
        // from inside the box's neighbourhood out to 0.2 m
        const scalar reach = 0.2 * std::pow(r.next(), 2);
        q[i] = point(0.025, 0.0025, 0.05) +
               vector(r.next() - 0.5, r.next() - 0.5, r.next() - 0.5) * 2 * reach;
    }
    return q;
}

// the direct sums
void direct(const Sources& s, const point& x, label p, scalar& weight, vector& sumT)
{
    weight = 0;
    sumT = Zero;
    forAll(s.x, i)
    {
        const scalar r2 = max(magSqr(x - s.x[i]), VSMALL);
        const scalar w = s.a[i] * inverseDistance::inversePower(r2, p);
        weight += w;
        sumT += w * s.t[i];
    }
}

// largest |tree - direct| of sumT / weight over the query points, relative to max |t|
scalar largestDeviation(const Sources& s, const pointField& q, scalar theta, scalar near)
{
    inverseDistanceTree tree(s.x, s.a, 5, theta);
    tree.setTranslations(s.t);
    const scalar tMax = max(mag(s.t));
    scalar worst = 0;
    for (const point& x : q)
    {
        scalar w0, w1;
        vector t0, t1;
        direct(s, x, 5, w0, t0);
        tree.sum(x, near, w1, t1, [](label, scalar, scalar) {});
        worst = max(worst, mag(t1 / w1 - t0 / w0) / tMax);
    }
    return worst;
}
} // namespace

TEST(InverseDistanceTree, OpeningAngleZeroIsTheDirectSum)
{
    const Sources s = foilLikeSources(2000);
    inverseDistanceTree tree(s.x, s.a, 5, 0);
    tree.setTranslations(s.t);
    for (const point& x : queryPoints(200))
    {
        scalar w0, w1;
        vector t0, t1;
        direct(s, x, 5, w0, t0);
        EXPECT_EQ(tree.sum(x, 0.02, w1, t1, [](label, scalar, scalar) {}), 0);
        EXPECT_LT(mag(w1 - w0), 1e-12 * w0);
        EXPECT_LT(mag(t1 - t0), 1e-12 * mag(t0) + VSMALL);
    }
}

TEST(InverseDistanceTree, NearestIsTheBruteForceNearest)
{
    const Sources s = foilLikeSources(2000);
    const inverseDistanceTree tree(s.x, s.a, 5, 0.2);
    for (const point& x : queryPoints(500))
    {
        scalar best = GREAT;
        forAll(s.x, i)
        {
            best = min(best, magSqr(x - s.x[i]));
        }
        scalar r2 = -1;
        const label i = tree.nearest(x, r2);
        ASSERT_GE(i, 0);
        EXPECT_EQ(r2, best);
        EXPECT_EQ(magSqr(x - s.x[i]), best);
    }
}

TEST(InverseDistanceTree, SourcesWithinTheNearDistanceAreVisitedExactly)
{
    const Sources s = foilLikeSources(2000);
    inverseDistanceTree tree(s.x, s.a, 5, 0.3);
    tree.setTranslations(s.t);
    const scalar near = 0.02;
    for (const point& x : queryPoints(100))
    {
        std::set<label> visited;
        scalar w;
        vector t;
        tree.sum(x, near, w, t,
                 [&](label i, scalar r2, scalar wi)
                 {
                     visited.insert(i);
                     EXPECT_DOUBLE_EQ(r2, max(magSqr(x - s.x[i]), VSMALL));
                     EXPECT_DOUBLE_EQ(wi, s.a[i] * inverseDistance::inversePower(r2, 5));
                 });
        forAll(s.x, i)
        {
            if (mag(x - s.x[i]) < near)
            {
                EXPECT_TRUE(visited.count(i)) << "source " << i << " within " << near << " m";
            }
        }
    }
}

TEST(InverseDistanceTree, FarClustersAreExpandedToThirdOrderInTheAngle)
{
    const Sources s = foilLikeSources(2000);
    const pointField q = queryPoints(400);
    const scalar d10 = largestDeviation(s, q, 0.1, 0.02);
    const scalar d20 = largestDeviation(s, q, 0.2, 0.02);
    std::printf("largest deviation of the translation / max |t|: angle 0.1: %.3g, 0.2: %.3g\n", d10,
                d20);
    EXPECT_LT(d10, 1e-3);
    EXPECT_LT(d20, 1e-2);
    EXPECT_LT(4 * d10, d20);
}
