// SPDX-License-Identifier: GPL-3.0-or-later
// Element kernels and the structural solver: patch tests, rigid motions, finite rotation,
// cantilever (coarse), factorization reuse, interface API, Newton safeguards.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"
#include "fe/ElementKernel.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{

const TestCell allCells[] = {TestCell::Tet4, TestCell::Tet10, TestCell::Hex8, TestCell::Hex20,
                             TestCell::Hex27};

mesh::Mesh skewedBlock(TestCell cell, std::array<int, 3> n = {2, 2, 2}, bool structuredTets = false)
{
    fsi::testing::BlockSpec spec;
    spec.cells = n;
    // hexes: trilinear (non-affine) cells; tets: straight-sided, irregular interior nodes
    spec.skew = cell == TestCell::Hex8 || cell == TestCell::Hex20 || cell == TestCell::Hex27;
    spec.structuredTets = structuredTets;
    const std::string file = fsi::testing::makeBlockMesh(
        fsi::testing::tempFile(std::string("block_") + fsi::testing::testCellName(cell) + ".msh"),
        cell, spec);
    return mesh::readGmsh(file, {"solid", {"x0", "x1", "y0", "z0", "boundary"}}, true);
}

// Linear field u = A X + c.
Eigen::Matrix3d gradient()
{
    Eigen::Matrix3d A;
    A << 1.0e-3, 2.0e-4, -3.0e-4, 0.5e-4, -0.7e-3, 1.1e-4, -2.2e-4, 0.3e-4, 0.4e-3;
    return A;
}
const Eigen::Vector3d offset(1e-3, -2e-3, 0.5e-3);

} // namespace

// Linear displacement on the boundary -> the same linear field inside (round-off) and a
// constant stress equal to D : eps, for every cell type on a skewed (non-affine) block.
TEST(PatchTest, LinearFieldExactConstantStress)
{
    const auto params = fsi::testing::elastic(2.0e5, 0.3);
    const auto law = material::makeMaterial(params, material::Kinematics::SmallStrain);
    const Eigen::Matrix3d A = gradient();
    const Eigen::Matrix3d eps = 0.5 * (A + A.transpose());
    material::Vector6 epsV;
    epsV << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(0, 1), 2 * eps(1, 2), 2 * eps(0, 2);
    const material::Vector6 sigma = law->initialTangent() * epsV;
    // The linear field prescribed on the group "boundary" of m, solved, compared inside.
    const auto check = [&](const mesh::Mesh& m, const std::string& name)
    {
        fe::ProblemDefinition p;
        fe::PrescribedDisplacement d;
        d.surface = "boundary";
        d.field = [&](const Eigen::Vector3d& X, double f) -> Eigen::Vector3d
        { return f * (A * X + offset); };
        p.displacements.push_back(d);
        fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
        ASSERT_GT(solver.numFreeDofs(), 0) << name;
        const auto report = solver.solve({0.0, 0.0});
        ASSERT_TRUE(report.converged) << name << ": " << report.message;
        double err = 0.0;
        for (int node = 0; node < m.numNodes(); ++node)
        {
            const Eigen::Vector3d exact = A * m.nodes.col(node) + offset;
            for (int i = 0; i < 3; ++i)
                err = std::max(err, std::abs(solver.displacement()[3 * node + i] - exact[i]));
        }
        std::vector<material::Vector6> nodal, cells;
        solver.cauchyStress(nodal, cells);
        double stressErr = 0.0;
        for (const auto& s : nodal)
            stressErr = std::max(stressErr, (s - sigma).norm() / sigma.norm());
        EXPECT_LT(err, 1e-12) << name;
        EXPECT_LT(stressErr, 1e-9) << name;
        std::printf(
            "patch test %-8s %4d cells: max |u - u_exact| = %.2e m, max stress error %.2e\n",
            name.c_str(), m.cells.size(), err, stressErr);
    };
    for (TestCell cell : allCells)
        check(skewedBlock(cell), fsi::testing::testCellName(cell));
    for (int q : {0, 15, 18})
    {
        const auto file = fsi::testing::makePrismBlock(fsi::testing::tempFile("prisms.msh"), q);
        check(mesh::readGmsh(file, {"solid", {"boundary"}}, true),
              "Prism" + std::to_string(q ? q : 6));
    }
}

// Rigid translation + infinitesimal rotation (small strain) and a finite 90-degree rotation
// (total Lagrangian) give zero stress and zero internal force, per cell.
TEST(ElementKernel, RigidMotionsAreStressFree)
{
    const auto params = fsi::testing::elastic(1.0e6, 0.3);
    const auto small = material::makeMaterial(params, material::Kinematics::SmallStrain);
    const auto tl = material::makeMaterial(params, material::Kinematics::TotalLagrangian);
    Eigen::Matrix3d W; // skew: infinitesimal rotation
    W << 0, -1e-3, 2e-3, 1e-3, 0, -0.5e-3, -2e-3, 0.5e-3, 0;
    const Eigen::Matrix3d R =
        (Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
    for (TestCell cell : allCells)
    {
        const mesh::Mesh m = skewedBlock(cell, {1, 1, 1});
        for (int c = 0; c < m.cells.size(); ++c)
        {
            const int n = m.cells.numNodes(c);
            Eigen::Matrix3Xd X(3, n), uSmall(3, n), uRot(3, n);
            for (int a = 0; a < n; ++a)
            {
                X.col(a) = m.nodes.col(m.cells.nodes(c)[a]);
                uSmall.col(a) = W * X.col(a) + offset;
                uRot.col(a) = (R - Eigen::Matrix3d::Identity()) * X.col(a) + offset;
            }
            std::vector<double> data;
            fe::appendCellQuadrature(m.cells.types[c], X, data);
            fe::CellQuadrature cq{n, static_cast<int>(data.size()) / (1 + 4 * n), data.data()};
            Eigen::VectorXd f;
            fe::cellResponse(cq, uSmall, *small, material::Kinematics::SmallStrain, {0, 0}, nullptr,
                             f, nullptr);
            EXPECT_LT(f.norm(), 1e-9) << fsi::testing::testCellName(cell);
            fe::cellResponse(cq, uRot, *tl, material::Kinematics::TotalLagrangian, {0, 0}, nullptr,
                             f, nullptr);
            EXPECT_LT(f.norm(), 1e-8) << fsi::testing::testCellName(cell) << " 90 degree rotation";
            // the same rotation under small strain is NOT stress free (sanity of the test)
            fe::cellResponse(cq, uRot, *small, material::Kinematics::SmallStrain, {0, 0}, nullptr,
                             f, nullptr);
            EXPECT_GT(f.norm(), 1e3);
        }
    }
}

// The consistent tangent equals the finite-difference derivative of the internal force (TL).
TEST(ElementKernel, TangentIsConsistent)
{
    const auto params = fsi::testing::elastic(1.0e6, 0.35);
    const auto tl = material::makeMaterial(params, material::Kinematics::TotalLagrangian);
    for (TestCell cell : {TestCell::Tet10, TestCell::Hex20})
    {
        const mesh::Mesh m = skewedBlock(cell, {1, 1, 1});
        const int n = m.cells.numNodes(0);
        Eigen::Matrix3Xd X(3, n), u(3, n);
        for (int a = 0; a < n; ++a)
        {
            X.col(a) = m.nodes.col(m.cells.nodes(0)[a]);
            u.col(a) = Eigen::Vector3d(0.1 * std::sin(3 * X(0, a)), 0.05 * X(0, a) * X(1, a),
                                       -0.08 * X(2, a) * X(2, a));
        }
        std::vector<double> data;
        fe::appendCellQuadrature(m.cells.types[0], X, data);
        fe::CellQuadrature cq{n, static_cast<int>(data.size()) / (1 + 4 * n), data.data()};
        Eigen::VectorXd f0, f1, f2;
        Eigen::MatrixXd K;
        fe::cellResponse(cq, u, *tl, material::Kinematics::TotalLagrangian, {0, 0}, nullptr, f0,
                         &K);
        const double h = 1e-7;
        double err = 0.0;
        for (int j = 0; j < 3 * n; ++j)
        {
            Eigen::Matrix3Xd up = u, um = u;
            up(j % 3, j / 3) += h;
            um(j % 3, j / 3) -= h;
            fe::cellResponse(cq, up, *tl, material::Kinematics::TotalLagrangian, {0, 0}, nullptr,
                             f1, nullptr);
            fe::cellResponse(cq, um, *tl, material::Kinematics::TotalLagrangian, {0, 0}, nullptr,
                             f2, nullptr);
            err = std::max(err, ((f1 - f2) / (2 * h) - K.col(j)).norm() / K.norm());
        }
        EXPECT_LT(err, 1e-7) << fsi::testing::testCellName(cell);
        EXPECT_LT((K - K.transpose()).norm(), 1e-9 * K.norm());
    }
}

// A finite 90-degree rotation of the whole boundary: with total Lagrangian kinematics the
// body rotates rigidly (zero stress); Newton needs the safeguards (load sub-stepping).
TEST(TotalLagrangian, NinetyDegreeRotationOfTheBlockIsStressFree)
{
    const auto params = fsi::testing::elastic(1.0e6, 0.3);
    const auto tl = material::makeMaterial(params, material::Kinematics::TotalLagrangian);
    const mesh::Mesh m = skewedBlock(TestCell::Tet10, {2, 2, 2});
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    fe::ProblemDefinition p;
    p.kinematics = material::Kinematics::TotalLagrangian;
    fe::PrescribedDisplacement d;
    d.surface = "boundary";
    d.field = [](const Eigen::Vector3d& X, double f) -> Eigen::Vector3d
    {
        const Eigen::Matrix3d Rf =
            Eigen::AngleAxisd(f * M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        return (Rf - Eigen::Matrix3d::Identity()) * X;
    };
    p.displacements.push_back(d);
    p.newton.residualTolerance = 1e-14; // quadratic convergence: cheap to go to round-off
    p.newton.maxIterations = 30;
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *tl, p);
    // the load factor is the rotation angle / 90 degrees. One solve at the full angle: the
    // interior starts at rest, the full step stalls and load sub-stepping must recover.
    const auto report = solver.solve({0, 0});
    ASSERT_TRUE(report.converged) << report.message;
    double err = 0.0;
    for (int node = 0; node < m.numNodes(); ++node)
    {
        const Eigen::Vector3d exact = (R - Eigen::Matrix3d::Identity()) * m.nodes.col(node);
        for (int i = 0; i < 3; ++i)
            err = std::max(err, std::abs(solver.displacement()[3 * node + i] - exact[i]));
    }
    std::vector<material::Vector6> nodal, cells;
    solver.cauchyStress(nodal, cells);
    double smax = 0.0;
    for (const auto& s : nodal)
        smax = std::max(smax, s.cwiseAbs().maxCoeff());
    std::printf("90-degree rotation: %d Newton iterations, %d load cuts, max |u - u_rigid| %.2e m, "
                "max |sigma| %.2e Pa\n",
                report.newtonIterations, report.loadCuts, err, smax);
    EXPECT_LT(err, 1e-8);
    EXPECT_LT(smax, 1e-6 * 1e6);
}

// Coarse slender cantilever: Tet10, 2 cells through the depth, within 0.5 % of Timoshenko.
// Small strain + linear elastic: one factorization for repeated solves of the same matrix.
TEST(Cantilever, CoarseTipDeflectionAndFactorizationReuse)
{
    fsi::testing::BlockSpec spec;
    spec.size = {2.0, 0.1, 0.1};
    spec.cells = {40, 1, 1}; // unstructured Tet10, h = 0.05
    const std::string file =
        fsi::testing::makeBlockMesh(fsi::testing::tempFile("beam.msh"), TestCell::Tet10, spec);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true);
    const double E = 2e9, P = 1000.0, L = 2.0, h = 0.1, b = 0.1, I = b * h * h * h / 12, G = E / 2;
    const double timoshenko = P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * b * h);
    const auto law =
        material::makeMaterial(fsi::testing::elastic(E, 0.0), material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"x0"};
    p.wetted = "x1";
    p.forces.push_back({"x1", Eigen::Vector3d(0, -P, 0)});
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    auto report = solver.solve({0, 0});
    ASSERT_TRUE(report.converged);
    const int tip = m.nearestNode(Eigen::Vector3d(2.0, 0.05, 0.05));
    const double uy = -solver.displacement()[3 * tip + 1];
    std::printf("coarse cantilever: tip %.6e m, Timoshenko %.6e m, error %.3f %%\n", uy, timoshenko,
                100 * (uy - timoshenko) / timoshenko);
    EXPECT_NEAR(uy, timoshenko, 0.02 * timoshenko);
    EXPECT_EQ(solver.factorizationCount(), 1);
    // the same loads again as interface forces at the wetted nodes: same answer, no refactorization
    solver.acceptLevel();
    const auto x = solver.wettedNodeCoordinates();
    ASSERT_EQ(x.size(), 3 * solver.wettedNodes().size());
    fe::ProblemDefinition q = p;
    q.forces.clear();
    fe::StructuralSolver coupled(MPI_COMM_WORLD, m, *law, q);
    // a uniform split of P over the wetted nodes: statically equivalent to the traction,
    // the tip deflection agrees up to the local end effect
    fe::InterfaceLoads loads;
    loads.forces.assign(x.size(), 0.0);
    for (std::size_t k = 0; k < solver.wettedNodes().size(); ++k)
        loads.forces[3 * k + 1] = -P / solver.wettedNodes().size();
    for (int level = 0; level < 3; ++level)
    {
        report = coupled.solve({double(level), level ? 1.0 : 0.0}, loads);
        ASSERT_TRUE(report.converged);
        coupled.acceptLevel();
    }
    EXPECT_NEAR(-coupled.displacement()[3 * tip + 1], timoshenko, 0.03 * timoshenko);
    EXPECT_EQ(coupled.factorizationCount(), 1);
    EXPECT_EQ(coupled.analysisCount(), 1);
    const auto ud = coupled.wettedNodeDisplacements();
    EXPECT_EQ(ud.size(), x.size());
}

// wettedFaces(): the wetted surface's faces over wetted-node indices (the nearest-projection
// mapping's source surface): each index names the face's own mesh node.
TEST(WettedFaces, IndexTheWettedNodesInTheirOrder)
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.2, 0.2};
    spec.cells = {5, 2, 2};
    const std::string file =
        fsi::testing::makeBlockMesh(fsi::testing::tempFile("wetted.msh"), TestCell::Tet10, spec);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true);
    const auto law =
        material::makeMaterial(fsi::testing::elastic(1e6, 0.3), material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"x0"};
    p.wetted = "x1";
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    const mesh::CellList local = solver.wettedFaces();
    const mesh::CellList& global = m.surface("x1").faces;
    ASSERT_EQ(local.size(), global.size());
    ASSERT_GT(local.size(), 0);
    const auto& wetted = solver.wettedNodes();
    for (int f = 0; f < local.size(); ++f)
    {
        EXPECT_EQ(local.types[std::size_t(f)], global.types[std::size_t(f)]);
        ASSERT_EQ(local.numNodes(f), global.numNodes(f));
        for (int a = 0; a < local.numNodes(f); ++a)
        {
            const int k = local.nodes(f)[a];
            ASSERT_GE(k, 0);
            ASSERT_LT(k, int(wetted.size()));
            EXPECT_EQ(wetted[std::size_t(k)], global.nodes(f)[a]);
        }
    }
}

// acceptLevel() refuses a level whose solve did not converge (never silently accepted).
TEST(Newton, StallIsReportedNotAccepted)
{
    const auto params = fsi::testing::elastic(1.0e6, 0.3);
    const auto tl = material::makeMaterial(params, material::Kinematics::TotalLagrangian);
    const mesh::Mesh m = skewedBlock(TestCell::Tet10, {1, 1, 1});
    fe::ProblemDefinition p;
    p.kinematics = material::Kinematics::TotalLagrangian;
    p.clamped = {"x0"};
    p.tractions.push_back({"x1", Eigen::Vector3d(-5e6, 0, 0)}); // crushes the block
    p.newton.maxIterations = 8;
    p.newton.maxLoadCuts = 2;
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *tl, p);
    const auto report = solver.solve({0, 0});
    EXPECT_FALSE(report.converged);
    EXPECT_FALSE(report.message.empty());
    EXPECT_THROW(solver.acceptLevel(), std::runtime_error);
    // the driver can fall back to the last accepted state and go on from there
    solver.rejectLevel();
    for (double u : solver.displacement())
        EXPECT_EQ(u, 0.0);
    EXPECT_NO_THROW(solver.acceptLevel());
    std::printf("stalled Newton reported: %s\n", report.message.c_str());
}

// Strains come from the displacement gradient, not from F - I: a strain of 1e-12 keeps its
// digits (F - I would leave about 4 of them), in both kinematics.
TEST(ElementKernel, TinyStrainsKeepTheirDigits)
{
    Eigen::Matrix3d H;
    H << 1.234567890123e-12, 2.0e-13, -3.0e-13, 4.0e-13, -5.55e-12, 6.0e-13, 7.0e-13, 8.0e-13,
        9.87e-12;
    for (auto kin : {material::Kinematics::SmallStrain, material::Kinematics::TotalLagrangian})
    {
        const auto e = fe::strainFromH(H, kin);
        const Eigen::Matrix3d sym = 0.5 * (H + H.transpose());
        const Eigen::Matrix3d exact = kin == material::Kinematics::SmallStrain
                                          ? sym
                                          : Eigen::Matrix3d(sym + 0.5 * H.transpose() * H);
        EXPECT_NEAR(e(0), exact(0, 0), 1e-15 * std::abs(exact(0, 0)));
        EXPECT_NEAR(e(1), exact(1, 1), 1e-15 * std::abs(exact(1, 1)));
        EXPECT_NEAR(e(2), exact(2, 2), 1e-15 * std::abs(exact(2, 2)));
        EXPECT_NEAR(e(3), 2 * exact(0, 1), 1e-15 * std::abs(exact(0, 1)));
    }
}
