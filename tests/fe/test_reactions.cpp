// SPDX-License-Identifier: GPL-3.0-or-later
// Reaction forces on clamped groups: in equilibrium they balance the applied loads,
// sum of reactions = -(total load), to the Newton tolerance; also after acceptLevel().
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

using namespace fsi;

namespace
{
mesh::Mesh beamMesh()
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.2, 0.2};
    spec.cells = {5, 1, 1};
    const auto file = fsi::testing::makeBlockMesh(fsi::testing::tempFile("reaction.msh"),
                                                  fsi::testing::TestCell::Tet10, spec);
    return mesh::readGmsh(file, {"solid", {"x0", "x1", "y1"}}, true);
}
} // namespace

TEST(Reactions, ClampedGroupBalancesTractionForceAndGravity)
{
    const mesh::Mesh m = beamMesh();
    for (auto kinematics :
         {material::Kinematics::SmallStrain, material::Kinematics::TotalLagrangian})
    {
        const auto law = material::makeMaterial(fsi::testing::elastic(1e7, 0.3), kinematics);
        fe::ProblemDefinition p;
        p.kinematics = kinematics;
        p.clamped = {"x0"};
        p.density = 1000.0;
        p.gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
        p.tractions.push_back({"x1", Eigen::Vector3d(2e3, -1e3, 500.0)}); // on 0.04 m^2
        p.forces.push_back({"y1", Eigen::Vector3d(0.0, -30.0, 10.0)});
        p.newton.residualTolerance = 1e-12;
        fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
        const auto report = solver.solve({0.0, 0.0});
        ASSERT_TRUE(report.converged) << report.message;
        const Eigen::Vector3d load = Eigen::Vector3d(2e3, -1e3, 500.0) * 0.04 +
                                     Eigen::Vector3d(0.0, -30.0, 10.0) +
                                     1000.0 * 0.2 * 0.2 * 1.0 * Eigen::Vector3d(0.0, -9.81, 0.0);
        const Eigen::Vector3d r = solver.reactionForce("x0");
        EXPECT_LT((r + load).norm(), 1e-9 * load.norm())
            << "reaction " << r.transpose() << " N, load " << load.transpose() << " N";
        // a surface without supports: the residual only
        EXPECT_LT(solver.reactionForce("x1").norm(), 1e-9 * load.norm());
        solver.acceptLevel();
        EXPECT_LT((solver.reactionForce("x0") + load).norm(), 1e-9 * load.norm());
        EXPECT_THROW(solver.reactionForce("nothere"), std::runtime_error);
    }
}

TEST(Reactions, ViscoelasticAcceptedLevelStillBalances)
{
    const mesh::Mesh m = beamMesh();
    material::MaterialParameters mp;
    mp.type = "viscoelastic";
    mp.youngsModulus = 1e7;
    mp.poissonRatio = 0.45;
    mp.modulusBasis = "long-term";
    mp.pronyConvention = "long-term-gamma";
    mp.pronyCoefficients = {1.0};
    mp.pronyTimes = {0.1};
    const auto law = material::makeMaterial(mp, material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"x0"};
    p.tractions.push_back({"x1", Eigen::Vector3d(0.0, -1e3, 0.0)});
    p.newton.residualTolerance = 1e-12;
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    for (int n = 0; n < 3; ++n)
    {
        ASSERT_TRUE(solver.solve({0.1 * n, n ? 0.1 : 0.0}).converged);
        solver.acceptLevel(); // the relaxation of the level must not be applied twice
        EXPECT_NEAR(solver.reactionForce("x0").y(), 40.0, 1e-9 * 40.0) << "level " << n;
    }
}
