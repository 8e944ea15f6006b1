// SPDX-License-Identifier: GPL-3.0-or-later
// The projected-dilatation hexahedra (B-bar in small strain, F-bar in total Lagrangian):
// patch tests, consistency of the tangent with the internal force, viscoelastic history through
// the solver, and the volumetric-locking warning.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"
#include "fe/ElementKernel.hpp"
#include "fe/Quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{

const TestCell hexCells[] = {TestCell::Hex8, TestCell::Hex20, TestCell::Hex27};

mesh::Mesh skewedHexBlock(TestCell cell, std::array<int, 3> n)
{
    fsi::testing::BlockSpec spec;
    spec.cells = n;
    spec.skew = true; // non-affine (trilinear) cells
    const std::string file = fsi::testing::makeBlockMesh(
        fsi::testing::tempFile(std::string("pd_block_") + fsi::testing::testCellName(cell) +
                               ".msh"),
        cell, spec);
    return mesh::readGmsh(file, {"solid", {"boundary"}}, true);
}

material::MaterialParameters viscoelastic(double E, double nu)
{
    material::MaterialParameters p;
    p.type = "viscoelastic";
    p.youngsModulus = E;
    p.poissonRatio = nu;
    p.modulusBasis = "long-term";
    p.pronyConvention = "long-term-gamma";
    p.pronyCoefficients = {0.5, 1.5};
    p.pronyTimes = {0.1, 2.0};
    return p;
}

material::MaterialParameters neoHookean(double E, double nu)
{
    material::MaterialParameters p = fsi::testing::elastic(E, nu);
    p.type = "neo-hookean";
    return p;
}

// One cell's quadrature data with the dilatation modes of the projected formulation.
struct OneCell
{
    std::vector<double> data;
    fe::CellQuadrature cq;
    Eigen::Matrix3Xd X;
};

OneCell oneCell(const mesh::Mesh& m, int c, fe::Formulation formulation)
{
    OneCell one;
    const int n = m.cells.numNodes(c);
    one.X.resize(3, n);
    for (int a = 0; a < n; ++a)
        one.X.col(a) = m.nodes.col(m.cells.nodes(c)[a]);
    const int modes = fe::dilatationModeCount(m.cells.types[c], formulation);
    fe::appendCellQuadrature(m.cells.types[c], one.X, one.data, modes);
    const int points = static_cast<int>(fe::quadrature(m.cells.types[c]).size());
    one.cq = fe::CellQuadrature{n, points, one.data.data(), modes};
    return one;
}

} // namespace

TEST(ProjectedDilatation, ModeCountsAndNames)
{
    using mesh::CellType;
    const auto pd = fe::Formulation::ProjectedDilatation;
    EXPECT_EQ(fe::dilatationModeCount(CellType::Hex8, pd), 1);
    EXPECT_EQ(fe::dilatationModeCount(CellType::Hex20, pd), 4);
    EXPECT_EQ(fe::dilatationModeCount(CellType::Hex27, pd), 4);
    EXPECT_EQ(fe::dilatationModeCount(CellType::Tet10, pd), 0);
    EXPECT_EQ(fe::dilatationModeCount(CellType::Hex27, fe::Formulation::Displacement), 0);
    EXPECT_EQ(fe::formulationFromName("projected-dilatation"), pd);
    EXPECT_STREQ(fe::formulationName(pd), "projected-dilatation");
    EXPECT_THROW(fe::formulationFromName("bbar"), std::invalid_argument);
}

// A linear displacement on the boundary of a skewed block -> the same linear field inside and
// a constant stress, small strain (linear elastic, nu = 0.4999) and total Lagrangian
// (neo-Hookean, a finite homogeneous deformation: stretches of 10-20 %, shear).
TEST(ProjectedDilatation, PatchTestSmallAndFiniteStrain)
{
    Eigen::Matrix3d A;
    A << 1.0e-3, 2.0e-4, -3.0e-4, 0.5e-4, -0.7e-3, 1.1e-4, -2.2e-4, 0.3e-4, 0.4e-3;
    const Eigen::Vector3d offset(1e-3, -2e-3, 0.5e-3);
    for (auto kinematics :
         {material::Kinematics::SmallStrain, material::Kinematics::TotalLagrangian})
    {
        const bool small = kinematics == material::Kinematics::SmallStrain;
        const Eigen::Matrix3d grad = small ? A : Eigen::Matrix3d(150.0 * A); // TL: finite
        const auto law = material::makeMaterial(
            small ? fsi::testing::elastic(2.0e5, 0.4999) : neoHookean(2.0e5, 0.45), kinematics);
        // exact stress: the law at the exact strain, pushed forward with the exact F
        const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad;
        const material::Vector6 strain = fe::strainFromH(grad, kinematics);
        material::Vector6 s;
        material::Matrix6 D;
        law->evaluate(strain, {0, 0}, nullptr, s, D);
        const material::Vector6 sigma = fe::cauchyFromMaterialStress(s, F, kinematics);
        for (TestCell cell : hexCells)
        {
            const mesh::Mesh m = skewedHexBlock(cell, {2, 2, 2});
            fe::ProblemDefinition p;
            p.kinematics = kinematics;
            p.formulation = fe::Formulation::ProjectedDilatation;
            fe::PrescribedDisplacement d;
            d.surface = "boundary";
            d.field = [&](const Eigen::Vector3d& X, double f) -> Eigen::Vector3d
            { return f * (grad * X + offset); };
            p.displacements.push_back(d);
            p.newton.residualTolerance = 1e-13;
            p.newton.absoluteTolerance = 1e-12;
            fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
            const auto report = solver.solve({0.0, 0.0});
            const std::string name = std::string(fsi::testing::testCellName(cell)) +
                                     (small ? " small strain" : " total Lagrangian");
            ASSERT_TRUE(report.converged) << name << ": " << report.message;
            double err = 0.0;
            for (int node = 0; node < m.numNodes(); ++node)
            {
                const Eigen::Vector3d exact = grad * m.nodes.col(node) + offset;
                for (int i = 0; i < 3; ++i)
                    err = std::max(err, std::abs(solver.displacement()[3 * node + i] - exact[i]));
            }
            std::vector<material::Vector6> nodal, cells;
            solver.cauchyStress(nodal, cells);
            double stressErr = 0.0;
            for (const auto& c : cells)
                stressErr = std::max(stressErr, (c - sigma).norm() / sigma.norm());
            EXPECT_LT(err, small ? 1e-12 : 1e-11) << name;
            EXPECT_LT(stressErr, 1e-8) << name;
            std::printf("projected-dilatation patch test %-22s max |u - u_exact| = %.2e, stress "
                        "error %.2e\n",
                        name.c_str(), err, stressErr);
        }
    }
}

// The tangent equals the central finite difference of the internal force, and is symmetric:
// small strain (B-bar) and total Lagrangian (F-bar) with neo-Hookean, St Venant-Kirchhoff and
// the viscoelastic law (dt > 0, non-zero history), on one skewed cell of each hexahedron.
TEST(ProjectedDilatation, TangentMatchesFiniteDifferenceOfTheResidual)
{
    struct Case
    {
        const char* name;
        material::MaterialParameters params;
        material::Kinematics kinematics;
    };
    const Case cases[] = {
        {"linear-elastic small", fsi::testing::elastic(1.0e6, 0.49),
         material::Kinematics::SmallStrain},
        {"viscoelastic small", viscoelastic(1.0e6, 0.49), material::Kinematics::SmallStrain},
        {"neo-hookean TL", neoHookean(1.0e6, 0.49), material::Kinematics::TotalLagrangian},
        {"st-venant-kirchhoff TL", fsi::testing::elastic(1.0e6, 0.45),
         material::Kinematics::TotalLagrangian},
        {"viscoelastic TL", viscoelastic(1.0e6, 0.45), material::Kinematics::TotalLagrangian}};
    for (TestCell cell : hexCells)
    {
        const mesh::Mesh m = skewedHexBlock(cell, {1, 1, 1});
        const OneCell one = oneCell(m, 0, fe::Formulation::ProjectedDilatation);
        const int n = one.cq.numNodes;
        Eigen::Matrix3Xd u(3, n);
        for (int a = 0; a < n; ++a)
        {
            const Eigen::Vector3d X = one.X.col(a);
            u.col(a) = Eigen::Vector3d(0.1 * std::sin(3 * X(0)) + 0.05 * X(2),
                                       0.05 * X(0) * X(1) - 0.04 * X(2) * X(2),
                                       -0.08 * X(2) * X(2) + 0.03 * X(0) * X(1));
        }
        for (const Case& c : cases)
        {
            const auto law = material::makeMaterial(c.params, c.kinematics);
            const std::size_t hs = law->historySize();
            std::vector<double> history(one.cq.numPoints * hs);
            for (std::size_t i = 0; i < history.size(); ++i)
                history[i] = 1.0e3 * std::sin(0.7 * static_cast<double>(i) + 0.3);
            const material::TimeStep step{0.3, 0.05};
            const double* h = hs ? history.data() : nullptr;
            Eigen::VectorXd f0, f1, f2;
            Eigen::MatrixXd K;
            fe::cellResponse(one.cq, u, *law, c.kinematics, step, h, f0, &K);
            const double eps = 1e-7;
            double err = 0.0;
            for (int j = 0; j < 3 * n; ++j)
            {
                Eigen::Matrix3Xd up = u, um = u;
                up(j % 3, j / 3) += eps;
                um(j % 3, j / 3) -= eps;
                fe::cellResponse(one.cq, up, *law, c.kinematics, step, h, f1, nullptr);
                fe::cellResponse(one.cq, um, *law, c.kinematics, step, h, f2, nullptr);
                err = std::max(err, ((f1 - f2) / (2 * eps) - K.col(j)).norm() / K.norm());
            }
            const std::string name = std::string(fsi::testing::testCellName(cell)) + " " + c.name;
            EXPECT_LT(err, 1e-7) << name;
            EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm()) << name;
            // the projected element is a different element: the plain tangent differs
            const OneCell plain = oneCell(m, 0, fe::Formulation::Displacement);
            Eigen::MatrixXd Kplain;
            fe::cellResponse(plain.cq, u, *law, c.kinematics, step, h, f1, &Kplain);
            EXPECT_GT((K - Kplain).norm(), 1e-3 * K.norm()) << name;
        }
    }
}

// Viscoelastic law through the solver with the projected Hex27: a homogeneous deformation held
// over three levels; the Cauchy stress of every cell equals the material-point recursion at the
// exact strain, pushed forward with the exact F (the history is updated with the projected
// strain, which is the exact one for a linear field). Small strain and total Lagrangian (a 5 %
// stretch with shear).
TEST(ProjectedDilatation, ViscoelasticRelaxationMatchesTheMaterialPoint)
{
    const mesh::Mesh m = skewedHexBlock(TestCell::Hex27, {2, 2, 1});
    for (auto kinematics :
         {material::Kinematics::SmallStrain, material::Kinematics::TotalLagrangian})
    {
        const bool small = kinematics == material::Kinematics::SmallStrain;
        const auto law = material::makeMaterial(viscoelastic(1.0e6, 0.499), kinematics);
        Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();
        grad(0, 0) = small ? 1e-3 : 5e-2;
        grad(0, 1) = small ? 4e-4 : 3e-2;
        fe::ProblemDefinition p;
        p.kinematics = kinematics;
        p.formulation = fe::Formulation::ProjectedDilatation;
        fe::PrescribedDisplacement d;
        d.surface = "boundary";
        d.field = [&](const Eigen::Vector3d& X, double f) -> Eigen::Vector3d
        { return f * (grad * X); };
        p.displacements.push_back(d);
        p.newton.residualTolerance = 1e-12;
        p.newton.absoluteTolerance = 1e-10;
        fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
        const material::Vector6 strain = fe::strainFromH(grad, kinematics);
        const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad;
        std::vector<double> h(law->historySize()), next(law->historySize());
        law->initialiseHistory(h.data());
        double t = 0.0;
        for (double dt : {0.0, 0.05, 0.2})
        {
            t += dt;
            const material::TimeStep step{t, dt};
            const auto report = solver.solve(step);
            ASSERT_TRUE(report.converged) << report.message;
            material::Vector6 s;
            material::Matrix6 D;
            law->evaluate(strain, step, h.data(), s, D);
            const material::Vector6 expected = fe::cauchyFromMaterialStress(s, F, kinematics);
            std::vector<material::Vector6> nodal, cells;
            solver.cauchyStress(nodal, cells);
            for (const auto& c : cells)
                EXPECT_LT((c - expected).norm(), 1e-8 * expected.norm())
                    << (small ? "small strain" : "total Lagrangian") << ", t = " << t;
            solver.acceptLevel();
            law->updateHistory(strain, step, h.data(), next.data());
            h.swap(next);
        }
    }
}

TEST(LockingWarning, CellTypesAndPoissonRatio)
{
    using mesh::CellType;
    const auto disp = fe::Formulation::Displacement, pd = fe::Formulation::ProjectedDilatation;
    const std::vector<CellType> hex27(3, CellType::Hex27);
    EXPECT_EQ(fe::lockingCellTypes(hex27, disp, 0.4999), std::vector<std::string>{"Hex27"});
    EXPECT_TRUE(fe::lockingCellTypes(hex27, pd, 0.4999).empty());
    EXPECT_TRUE(fe::lockingCellTypes(hex27, disp, 0.3).empty());
    EXPECT_EQ(fe::lockingCellTypes({CellType::Hex8, CellType::Tet4}, pd, 0.49),
              std::vector<std::string>{"Tet4"});
    EXPECT_EQ(fe::lockingCellTypes({CellType::Hex20, CellType::Hex8}, disp, 0.45),
              (std::vector<std::string>{"Hex20", "Hex8"}));
    EXPECT_TRUE(fe::lockingCellTypes({CellType::Tet10}, disp, 0.4999).empty());
    EXPECT_TRUE(fe::lockingCellTypes({CellType::Prism15, CellType::Prism18}, disp, 0.4999).empty());
    EXPECT_EQ(fe::lockingCellTypes({CellType::Prism6}, pd, 0.4999),
              std::vector<std::string>{"Prism6"});
    // the effective Poisson ratio of a viscoelastic law is the long-term (most incompressible)
    auto visco = viscoelastic(1.0e6, 0.45); // E, nu long-term
    const auto law = material::makeMaterial(visco, material::Kinematics::SmallStrain);
    EXPECT_NEAR(fe::effectivePoissonRatio(*law), 0.45, 1e-9);
    const auto elastic = material::makeMaterial(fsi::testing::elastic(1.0, 0.4999),
                                                material::Kinematics::SmallStrain);
    EXPECT_NEAR(fe::effectivePoissonRatio(*elastic), 0.4999, 1e-12);
}

// The solver prints one warning line for a locking combination and none otherwise.
TEST(LockingWarning, PrintedOnceAtStartUp)
{
    const mesh::Mesh m = skewedHexBlock(TestCell::Hex27, {1, 1, 1});
    const auto law = material::makeMaterial(fsi::testing::elastic(1.0, 0.4999),
                                            material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"boundary"};
    ::testing::internal::CaptureStderr();
    {
        fe::StructuralSolver locking(MPI_COMM_WORLD, m, *law, p);
    }
    const std::string warned = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warned.find("warning: "), std::string::npos) << warned;
    EXPECT_NE(warned.find("Hex27"), std::string::npos) << warned;
    EXPECT_NE(warned.find("projected-dilatation"), std::string::npos) << warned;
    EXPECT_EQ(std::count(warned.begin(), warned.end(), '\n'), 1) << warned;
    p.formulation = fe::Formulation::ProjectedDilatation;
    ::testing::internal::CaptureStderr();
    {
        fe::StructuralSolver fine(MPI_COMM_WORLD, m, *law, p);
    }
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}
