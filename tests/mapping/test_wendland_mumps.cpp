// SPDX-License-Identifier: GPL-3.0-or-later
// rbf-wendland-c2 with solver mumps (MUMPS LDL^T on MPI_COMM_SELF): the same mapping as Eigen's
// direct LDLT to round-off, with the exact properties (linear fields, total force and moment).
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
