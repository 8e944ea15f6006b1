// SPDX-License-Identifier: GPL-3.0-or-later
// The linear re-solve of a level (small strain, a law linear in the strain): a second solve at
// the same step with new interface loads is one back-substitution with the level's
// factorization and gives the same displacement as a fresh solve with those loads.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{
mesh::Mesh beam()
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.1, 0.1};
    spec.cells = {10, 2, 2};
    const std::string file =
        fsi::testing::makeBlockMesh(fsi::testing::tempFile("linear_update_beam.msh"), TestCell::Tet10, spec);
    return mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true);
}

material::MaterialParameters viscoelastic()
{
    return fsi::testing::viscoelasticKG(5e7, 1e7, {0.5}, {2.0});
}

fe::InterfaceLoads tipLoad(std::size_t wetted, double fy, double fz)
{
    fe::InterfaceLoads loads;
    loads.forces.assign(3 * wetted, 0.0);
    for (std::size_t k = 0; k < wetted; ++k)
    {
        loads.forces[3 * k + 1] = fy / wetted;
        loads.forces[3 * k + 2] = fz / wetted;
    }
    return loads;
}
} // namespace

TEST(LinearUpdate, ReSolveWithNewLoadsEqualsAFreshSolve)
{
    const mesh::Mesh m = beam();
    const auto law = material::makeMaterial(viscoelastic(), material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"x0"};
    p.wetted = "x1";
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    const std::size_t n = solver.wettedNodes().size();
    // level 0 and level 1 (dt 0.5 s: history acts), each re-solved with changed loads
    ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
    solver.acceptLevel();
    ASSERT_TRUE(solver.solve({0.5, 0.5}, tipLoad(n, -10, 0)).converged);
    const int factorizations = solver.factorizationCount();
    const auto again = solver.solve({0.5, 0.5}, tipLoad(n, -12, 3));
    ASSERT_TRUE(again.converged);
    EXPECT_NE(again.message.find("linear update"), std::string::npos) << again.message;
    EXPECT_EQ(again.newtonIterations, 1);
    EXPECT_EQ(solver.factorizationCount(), factorizations);

    // reference: the same history, the second loads solved by Newton directly
    fe::StructuralSolver fresh(MPI_COMM_WORLD, m, *law, p);
    ASSERT_TRUE(fresh.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
    fresh.acceptLevel();
    const auto direct = fresh.solve({0.5, 0.5}, tipLoad(n, -12, 3));
    ASSERT_TRUE(direct.converged);
    EXPECT_EQ(direct.message.find("linear update"), std::string::npos);
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < solver.displacement().size(); ++i)
    {
        diff = std::max(diff, std::abs(solver.displacement()[i] - fresh.displacement()[i]));
        scale = std::max(scale, std::abs(fresh.displacement()[i]));
    }
    EXPECT_LT(diff, 1e-9 * scale); // Newton's relative tolerance is 1e-8 of the force

    // a new step (the history moved on) is never a linear update
    solver.acceptLevel();
    const auto next = solver.solve({1.0, 0.5}, tipLoad(n, -12, 3));
    ASSERT_TRUE(next.converged);
    EXPECT_EQ(next.message.find("linear update"), std::string::npos);
}

// Finite strain is nonlinear: every solve runs Newton.
TEST(LinearUpdate, FiniteStrainAlwaysRunsNewton)
{
    const mesh::Mesh m = beam();
    const auto law = material::makeMaterial(viscoelastic(), material::Kinematics::TotalLagrangian);
    fe::ProblemDefinition p;
    p.kinematics = material::Kinematics::TotalLagrangian;
    p.clamped = {"x0"};
    p.wetted = "x1";
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    const std::size_t n = solver.wettedNodes().size();
    ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
    const auto again = solver.solve({0.0, 0.0}, tipLoad(n, -12, 0));
    ASSERT_TRUE(again.converged);
    EXPECT_EQ(again.message.find("linear update"), std::string::npos);
}
