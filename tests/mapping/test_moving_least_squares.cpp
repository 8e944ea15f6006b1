// SPDX-License-Identifier: GPL-3.0-or-later
// moving-least-squares: linear fields exact wherever the stencil spans them (inside a thin
// two-sided section too), the surface value carried along the normal off a flat patch, total
// force and moment kept by the transpose, no jumps between neighbouring targets, and each
// target's row independent of the other targets.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/MovingLeastSquares.hpp"
#include "mapping/Registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using namespace fsi::mapping;
using fsi::mapping::test::faceForces;
using fsi::mapping::test::linearField;
using fsi::mapping::test::plate;
using fsi::mapping::test::solidCylinder;
using fsi::mapping::test::totalMoment;

namespace
{

// The two sides of a thin plate section: z = 0.2 and z = 0.2 + gap, n x n nodes each over
// 1 m x 1 m, the upper side shifted by a third of a step (as two meshed faces would be).
PointCloud thinSection(int n, double gap)
{
    const PointCloud lower = plate(n, n, 1.0, 1.0, 0.0, 0.0);
    PointCloud upper = plate(n, n, 1.0, 1.0, 1.0 / (3.0 * (n - 1)), 0.0);
    upper.col(2).array() += gap;
    PointCloud both(lower.rows() + upper.rows(), 3);
    both << lower, upper;
    return both;
}

// Random points inside [0.1, 0.9]^2 x [zLo, zHi].
PointCloud randomPoints(int n, double zLo, double zHi, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0.1, 0.9), z(zLo, zHi);
    PointCloud p(n, 3);
    for (int i = 0; i < n; ++i)
        p.row(i) << u(random), u(random), z(random);
    return p;
}

MovingLeastSquares computed(const PointCloud& source, const PointCloud& target,
                            const MovingLeastSquaresParameters& params = {})
{
    MovingLeastSquares m(params);
    m.compute(source, target);
    return m;
}

} // namespace

TEST(MovingLeastSquares, ReproducesLinearFieldsInsideAThinSection)
{
    // gap a fifth of the node spacing: every stencil holds both sides, so it spans all three
    // directions and a point between the sides takes the linear field there (e.g. a section's
    // rotation, ux = -theta z), not the value of the closer side
    const double gap = 0.2 / 20.0;
    const PointCloud source = thinSection(21, gap);
    const PointCloud target = randomPoints(400, 0.2, 0.2 + gap, 7);
    const MovingLeastSquares m = computed(source, target);
    Values mapped(target.rows(), 3);
    m.applyConsistent(linearField(source), mapped);
    const Values exact = linearField(target);
    EXPECT_LT((mapped - exact).cwiseAbs().maxCoeff(), 1e-11 * exact.cwiseAbs().maxCoeff());
    EXPECT_LT(m.maxGap(), 0.05); // within a node spacing of the nodes
}

TEST(MovingLeastSquares, CarriesTheSurfaceValueAlongTheNormalOffAFlatPatch)
{
    // one flat side only: the fit cannot see a gradient along z and leaves it out, so a target
    // 0.3 spacings above the plate takes the linear field's value at its projection
    const PointCloud source = plate(21, 21, 1.0, 1.0, 0.0, 0.0);
    const PointCloud target = randomPoints(200, 0.215, 0.215, 3);
    PointCloud projected = target;
    projected.col(2).setConstant(0.2);
    const MovingLeastSquares m = computed(source, target);
    Values mapped(target.rows(), 3);
    m.applyConsistent(linearField(source), mapped);
    const Values expected = linearField(projected);
    EXPECT_LT((mapped - expected).cwiseAbs().maxCoeff(), 1e-11 * expected.cwiseAbs().maxCoeff());
}

TEST(MovingLeastSquares, TransposeKeepsTotalForceAndMoment)
{
    const double gap = 0.01;
    const PointCloud source = thinSection(21, gap);
    const PointCloud target = randomPoints(500, 0.2, 0.2 + gap, 11);
    const MovingLeastSquares m = computed(source, target);
    const Values forces = faceForces(target.rows());
    Values nodal(source.rows(), 3);
    m.applyConservative(forces, nodal);
    EXPECT_LT((nodal.colwise().sum() - forces.colwise().sum()).norm(), 1e-11 * forces.norm());
    EXPECT_LT((totalMoment(source, nodal) - totalMoment(target, forces)).norm(),
              1e-11 * forces.norm());
}

TEST(MovingLeastSquares, HasNoJumpsBetweenNeighbouringTargets)
{
    // a smooth non-linear field on the cylinder's nodes, sampled along a line on the surface in
    // steps of 1e-4 m: stencils change many times along it (nodes 0.13 m apart), yet no step of
    // the mapped value exceeds a few times the field's largest slope times the step
    const PointCloud source = solidCylinder(24);
    Values f(source.rows(), 3);
    for (Eigen::Index i = 0; i < source.rows(); ++i)
    {
        const double x = source(i, 0), y = source(i, 1), z = source(i, 2);
        f.row(i) << std::sin(3.0 * z), std::cos(2.0 * x) * z, y * y;
    }
    const double slope = 4.5; // bounds |grad| of every component on the cylinder
    const double step = 1e-4;
    const int n = 4000; // 0.4 m of axial line at theta = 0.3 rad
    PointCloud line(n, 3);
    for (int i = 0; i < n; ++i)
        line.row(i) << 1.0 + 0.5 * std::cos(0.3), -2.0 + 0.5 * std::sin(0.3), 0.3 + step * i;
    const MovingLeastSquares m = computed(source, line);
    Values mapped(n, 3);
    m.applyConsistent(f, mapped);
    double largestStep = 0.0;
    for (int i = 1; i < n; ++i)
        largestStep =
            std::max(largestStep, (mapped.row(i) - mapped.row(i - 1)).cwiseAbs().maxCoeff());
    EXPECT_LT(largestStep, 3.0 * slope * step);
}

TEST(MovingLeastSquares, EachTargetsRowIgnoresTheOtherTargets)
{
    // the property target-side smoothing lacks: a finer fluid mesh samples the same field
    const PointCloud source = thinSection(15, 0.01);
    const PointCloud coarse = randomPoints(50, 0.2, 0.21, 5);
    PointCloud fine(coarse.rows() + 300, 3);
    fine << coarse, randomPoints(300, 0.2, 0.21, 6);
    Values f(source.rows(), 3);
    for (Eigen::Index i = 0; i < source.rows(); ++i)
        f.row(i) << std::sin(5.0 * source(i, 0)), source(i, 1) * source(i, 1), source(i, 2);
    Values onCoarse(coarse.rows(), 3), onFine(fine.rows(), 3);
    computed(source, coarse).applyConsistent(f, onCoarse);
    computed(source, fine).applyConsistent(f, onFine);
    EXPECT_EQ((onFine.topRows(coarse.rows()) - onCoarse).cwiseAbs().maxCoeff(), 0.0);
}

TEST(MovingLeastSquares, RefusesBadParametersAndTooFewSources)
{
    const auto message = [](MovingLeastSquaresParameters p)
    {
        try
        {
            p.validate();
        }
        catch (const std::runtime_error& e)
        {
            return std::string(e.what());
        }
        return std::string();
    };
    MovingLeastSquaresParameters p;
    EXPECT_EQ(message(p), "");
    p.neighbours = 3;
    EXPECT_NE(message(p).find("moving-least-squares.neighbours must be in [4, 100]"),
              std::string::npos);
    p = {};
    p.radiusFactor = 1.0;
    EXPECT_NE(message(p).find("moving-least-squares.radius_factor must be in [1.05, 5]"),
              std::string::npos);
    p = {};
    p.cutoff = 0.0;
    EXPECT_NE(message(p).find("moving-least-squares.cutoff must be in (0, 0.5]"),
              std::string::npos);
    MovingLeastSquares m;
    EXPECT_THROW(m.compute(plate(1, 3, 1.0, 1.0, 0.0, 0.0), plate(2, 2, 1.0, 1.0, 0.0, 0.0)),
                 std::runtime_error);
    EXPECT_EQ(mappingType("moving-least-squares").defaults().type(), "moving-least-squares");
}
