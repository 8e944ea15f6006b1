// SPDX-License-Identifier: GPL-3.0-or-later
// rbf-wendland-c2 with solver mumps (MUMPS LDL^T on MPI_COMM_SELF): the same mapping as Eigen's
// direct LDLT to round-off, with the exact properties (linear fields, total force and moment);
// and buildMappings()' shared source system on every backend (mumps, direct, iterative).
// MPI is initialised by tests/linalg/MpiEnvironment.cpp (one rank).
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <gtest/gtest.h>

using namespace fsi::mapping;
using namespace fsi::mapping::test;

namespace
{

MappingParameters wendland(const std::string& solver)
{
    MappingParameters p;
    p.strategy = mappingType("rbf-wendland-c2").defaults();
    auto* w = p.strategy.get<WendlandParameters>();
    w->supportRadius = 0.4; // m: about 3 solid spacings at nTheta = 24
    w->solver = solver;
    return p;
}

} // namespace

TEST(WendlandMumps, MatchesEigenDirectAndKeepsTheExactProperties)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    const auto direct = buildMapping(wendland("direct"), s, t);
    const auto mumps = buildMapping(wendland("mumps"), s, t);

    // consistent: a smooth field to round-off of the two factorisations, linear fields exactly
    const Values smooth = linearField(s).array().sin();
    Values um(t.rows(), 3), ud(t.rows(), 3);
    mumps->applyConsistent(smooth, um);
    direct->applyConsistent(smooth, ud);
    EXPECT_LT((um - ud).norm() / ud.norm(), 1e-10);
    mumps->applyConsistent(linearField(s), um);
    EXPECT_LT(relativeMaxError(um, linearField(t)), 1e-10);

    // conservative: the same nodal forces; total force and moment to round-off
    const Values g = faceForces(t.rows());
    Values fm(s.rows(), 3), fd(s.rows(), 3);
    mumps->applyConservative(g, fm);
    direct->applyConservative(g, fd);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    const double momentScale = forceScale * Values(t).rowwise().norm().maxCoeff();
    EXPECT_LT((fm - fd).norm() / fd.norm(), 1e-10);
    EXPECT_LT((fm.colwise().sum() - g.colwise().sum()).norm() / forceScale, 1e-12);
    EXPECT_LT((totalMoment(s, fm) - totalMoment(t, g)).norm() / momentScale, 1e-12);
}

TEST(WendlandMumps, AutoChoosesMumpsWhenMpiRuns)
{
    const PointCloud s = solidCylinder(16), t = fluidCylinder(16);
    RbfWendlandC2 automatic(*wendland("auto").strategy.get<WendlandParameters>());
    automatic.compute(s, t);
    EXPECT_EQ(automatic.solverInUse(), "mumps");
    RbfWendlandC2 eigen(*wendland("direct").strategy.get<WendlandParameters>());
    eigen.compute(s, t);
    EXPECT_EQ(eigen.solverInUse(), "direct");
}

// buildMappings(): the second target's mapping shares the first's source system (one
// factorisation of Phi) and maps exactly as a mapping computed on its own; the first is not
// disturbed by the second's applies (they share the solver). Every backend.
class WendlandSharedSource : public ::testing::TestWithParam<std::string>
{
};

TEST_P(WendlandSharedSource, SecondTargetMapsAsItsOwnMapping)
{
    const PointCloud s = solidCylinder(24), points = fluidCylinder(24), faces = fluidCylinder(20);
    const auto p = wendland(GetParam());
    const auto maps = buildMappings(p, s, {&points, &faces});
    ASSERT_EQ(maps.size(), 2u);
    const auto* first = dynamic_cast<const RbfWendlandC2*>(maps[0].get());
    const auto* second = dynamic_cast<const RbfWendlandC2*>(maps[1].get());
    ASSERT_NE(first, nullptr);
    ASSERT_NE(second, nullptr);
    EXPECT_TRUE(second->sharesSourceWith(*first));
    EXPECT_EQ(second->sourceSize(), s.rows());
    EXPECT_EQ(second->targetSize(), faces.rows());
    EXPECT_EQ(second->solverInUse(), GetParam());

    const auto ownFaces = buildMapping(p, s, faces);
    const auto ownPoints = buildMapping(p, s, points);
    EXPECT_FALSE(dynamic_cast<const RbfWendlandC2&>(*ownFaces).sharesSourceWith(*first));

    const Values smooth = linearField(s).array().sin();
    Values shared(faces.rows(), 3), own(faces.rows(), 3);
    maps[1]->applyConsistent(smooth, shared);
    ownFaces->applyConsistent(smooth, own);
    EXPECT_LT((shared - own).norm() / own.norm(), 1e-12);
    maps[1]->applyConsistent(linearField(s), shared);
    EXPECT_LT(relativeMaxError(shared, linearField(faces)), 1e-10);

    // conservative from the second target: the same nodal forces, total force to round-off
    const Values g = faceForces(faces.rows());
    Values fShared(s.rows(), 3), fOwn(s.rows(), 3);
    maps[1]->applyConservative(g, fShared);
    ownFaces->applyConservative(g, fOwn);
    EXPECT_LT((fShared - fOwn).norm() / fOwn.norm(), 1e-12);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    EXPECT_LT((fShared.colwise().sum() - g.colwise().sum()).norm() / forceScale, 1e-12);

    // the first mapping after the second's applies
    Values firstShared(points.rows(), 3), firstOwn(points.rows(), 3);
    maps[0]->applyConsistent(smooth, firstShared);
    ownPoints->applyConsistent(smooth, firstOwn);
    EXPECT_LT((firstShared - firstOwn).norm() / firstOwn.norm(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Backends, WendlandSharedSource,
                         ::testing::Values("mumps", "direct", "iterative"));

// A second target with a point outside every support is refused as buildMapping() refuses it,
// and a strategy with nothing to share (nearest-neighbour) is computed on its own.
TEST(BuildMappings, RefusesAStrayTargetAndFallsBackWithoutSharing)
{
    const PointCloud s = solidCylinder(24), points = fluidCylinder(24);
    PointCloud stray = fluidCylinder(20);
    stray.row(3) << 1.0, -2.0, 2.0; // on the axis 1 m beyond the end: 1.1 m from every node
    auto p = wendland("direct");
    p.overlapTolerance = 10.0; // let the overlap check pass: the mapping's own check refuses it
    EXPECT_THROW(buildMappings(p, s, {&points, &stray}), std::runtime_error);
    try
    {
        buildMappings(p, s, {&points, &stray});
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("support_radius"), std::string::npos) << e.what();
    }

    MappingParameters nearest;
    const PointCloud faces = fluidCylinder(20);
    const auto maps = buildMappings(nearest, s, {&points, &faces});
    ASSERT_EQ(maps.size(), 2u);
    const auto own = buildMapping(nearest, s, faces);
    const Values field = linearField(s);
    Values a(faces.rows(), 3), b(faces.rows(), 3);
    maps[1]->applyConsistent(field, a);
    own->applyConsistent(field, b);
    EXPECT_EQ(a, b);
}
