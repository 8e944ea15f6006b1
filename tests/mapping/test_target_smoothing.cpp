// SPDX-License-Identifier: GPL-3.0-or-later
// mapping.smoothing_radius: the moving-least-squares smoother on the target cloud reproduces
// linear fields exactly, its transpose keeps total force and moment, it damps what varies below
// its radius, and a smoothed mapping keeps the strategy's exact properties.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/Registry.hpp"
#include "mapping/TargetSmoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

using namespace fsi::mapping;
using fsi::mapping::test::corner;
using fsi::mapping::test::faceForces;
using fsi::mapping::test::fluidCylinder;
using fsi::mapping::test::linearField;
using fsi::mapping::test::solidCylinder;
using fsi::mapping::test::totalMoment;

TEST(TargetSmoothing, ReproducesLinearFieldsOnCurvedFlatAndCornerClouds)
{
    // curved (cylinder), flat patches meeting at a corner (coplanar neighbourhoods: the
    // minimum-norm fit), and a radius that catches no neighbour for some points
    for (const PointCloud& points : {fluidCylinder(24), corner(17, 0.3, 0.0)})
        for (const double radius : {0.02, 0.15, 0.4})
        {
            const SmoothingOperator S = movingLeastSquaresSmoother(points, radius);
            const Values f = linearField(points);
            const Values smoothed = S * f;
            EXPECT_LT((smoothed - f).cwiseAbs().maxCoeff(), 1e-11 * f.cwiseAbs().maxCoeff())
                << "radius " << radius;
        }
}

TEST(TargetSmoothing, TransposeKeepsTotalForceAndMoment)
{
    const PointCloud points = corner(17, 0.3, 0.0);
    const SmoothingOperator S = movingLeastSquaresSmoother(points, 0.2);
    const Values forces = faceForces(points.rows());
    const Values moved = S.transpose() * forces;
    EXPECT_LT((moved.colwise().sum() - forces.colwise().sum()).norm(), 1e-11 * forces.norm());
    EXPECT_LT((totalMoment(points, moved) - totalMoment(points, forces)).norm(),
              1e-11 * forces.norm());
}

TEST(TargetSmoothing, DampsVariationBelowTheRadius)
{
    // a linear field plus point-to-point noise: the smoothed field keeps the linear part and
    // leaves less than half of the noise (each fit averages a few tens of points)
    const PointCloud points = fluidCylinder(32);
    std::mt19937 random(4);
    std::uniform_real_distribution<double> noise(-1.0, 1.0);
    const Values f = linearField(points);
    Values rough = f;
    for (Eigen::Index i = 0; i < rough.size(); ++i)
        rough.data()[i] += 1e-3 * noise(random);
    const SmoothingOperator S = movingLeastSquaresSmoother(points, 0.25);
    const double before = (rough - f).norm(), after = (S * rough - f).norm();
    EXPECT_LT(after, 0.5 * before);
}

TEST(TargetSmoothing, SmoothedMappingKeepsConsistencyAndConservation)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    MappingParameters p;
    p.strategy = mappingType("rbf-pu").defaults(); // reproduces linear fields
    p.smoothingRadius = 0.1;
    const auto map = buildMapping(p, s, t);
    EXPECT_EQ(map->name(), "rbf-pu");
    EXPECT_EQ(map->targetSize(), t.rows());
    EXPECT_EQ(map->sourceSize(), s.rows());
    Values mapped(t.rows(), 3);
    map->applyConsistent(linearField(s), mapped);
    EXPECT_LT((mapped - linearField(t)).cwiseAbs().maxCoeff(), 1e-6);
    const Values forces = faceForces(t.rows());
    Values nodal(s.rows(), 3);
    map->applyConservative(forces, nodal);
    EXPECT_LT((nodal.colwise().sum() - forces.colwise().sum()).norm(), 1e-10 * forces.norm());
    EXPECT_LT((totalMoment(s, nodal) - totalMoment(t, forces)).norm(), 1e-8 * forces.norm());
}

TEST(TargetSmoothing, RadiusZeroIsOffAndNegativeRadiiAreRefused)
{
    const PointCloud s = solidCylinder(12), t = fluidCylinder(12);
    MappingParameters p;
    const auto plain = buildMapping(p, s, t);
    EXPECT_EQ(dynamic_cast<const SmoothedMapping*>(plain.get()), nullptr);
    p.smoothingRadius = -1e-4;
    EXPECT_THROW(buildMapping(p, s, t), std::runtime_error);
    EXPECT_THROW(movingLeastSquaresSmoother(t, 0.0), std::runtime_error);
}
