// SPDX-License-Identifier: GPL-3.0-or-later
// The assembler's path end to end: METIS element partition -> each rank builds the CSR
// pattern of ITS elements (lower triangle) and assembles them -> SparseDirectSolver with
// duplicates summed across ranks -> solveSummedRhs. P1 tetrahedra for the Laplacian with
// a linear Dirichlet field reproduce it exactly (patch test), on any number of ranks.
#include "linalg/CsrPattern.hpp"
#include "linalg/Partition.hpp"
#include "linalg/SparseDirectSolver.hpp"
#include "CubeMesh.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>

using namespace fsi::linalg;

namespace
{
// m^3 cubes on [0,1]^3, 6 tets each (Kuhn), interior nodes slightly distorted.
struct TetMesh
{
    std::vector<Eigen::Vector3d> x;
    std::vector<bool> boundary;
    std::vector<std::vector<int>> tets;
};

TetMesh cubeTets(int m)
{
    const int nodesPerSide = m + 1;
    auto node = [m](int i, int j, int k) { return fsi::testing::cubeNode(m, i, j, k); };
    TetMesh mesh;
    mesh.x.resize(nodesPerSide * nodesPerSide * nodesPerSide);
    mesh.boundary.resize(mesh.x.size());
    for (int k = 0; k <= m; ++k)
        for (int j = 0; j <= m; ++j)
            for (int i = 0; i <= m; ++i)
            {
                const bool b = i == 0 || j == 0 || k == 0 || i == m || j == m || k == m;
                const double shift = b ? 0.0 : 0.15 / m * std::sin(i + 2.0 * j + 3.0 * k);
                mesh.x[node(i, j, k)] =
                    Eigen::Vector3d(i, j, k) / m + Eigen::Vector3d::Constant(shift);
                mesh.boundary[node(i, j, k)] = b;
            }
    mesh.tets = fsi::testing::cubeElements(m, true);
    return mesh;
}

// Gradients of the 4 barycentric functions (rows) and the volume of a tet.
Eigen::Matrix<double, 4, 3> gradients(const TetMesh& mesh, const std::vector<int>& t,
                                      double& volume)
{
    Eigen::Matrix3d jacobian;
    for (int c = 0; c < 3; ++c)
        jacobian.col(c) = mesh.x[t[c + 1]] - mesh.x[t[0]];
    volume = std::abs(jacobian.determinant()) / 6.0;
    Eigen::Matrix<double, 4, 3> grad;
    grad.bottomRows<3>() = jacobian.inverse();
    grad.row(0) = -grad.bottomRows<3>().colwise().sum();
    return grad;
}

int commRank()
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int commSize()
{
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}
} // namespace

TEST(DistributedAssembly, LinearFieldIsReproducedExactly)
{
    const int rank = commRank(), size = commSize();

    const TetMesh mesh = cubeTets(8);
    const auto& x = mesh.x;
    const auto& boundary = mesh.boundary;
    const auto& tets = mesh.tets;
    const int numNodes = static_cast<int>(x.size());
    auto exact = [&](int a) { return 1.0 + x[a](0) + 2.0 * x[a](1) - 3.0 * x[a](2); };

    // equations for interior nodes only
    std::vector<int> equation(numNodes, -1);
    int n = 0;
    for (int a = 0; a < numNodes; ++a)
        if (!boundary[a])
            equation[a] = n++;

    const std::vector<int> part = partitionElements(tets, size);
    std::vector<std::vector<int>> myDofs;
    std::vector<int> mine;
    for (std::size_t e = 0; e < tets.size(); ++e)
        if (part[e] == rank)
        {
            mine.push_back(static_cast<int>(e));
            std::vector<int> dofs;
            for (int a : tets[e])
                dofs.push_back(equation[a]);
            myDofs.push_back(dofs);
        }
    EXPECT_FALSE(mine.empty());
    const CsrPattern pattern = CsrPattern::fromElements(n, myDofs, true);
    std::vector<double> values(pattern.nonZeros(), 0.0), rhs(n, 0.0);
    for (int e : mine)
    {
        const auto& t = tets[e];
        double volume = 0.0;
        const Eigen::Matrix<double, 4, 3> grad = gradients(mesh, t, volume);
        const Eigen::Matrix4d ke = volume * grad * grad.transpose();
        for (int a = 0; a < 4; ++a)
        {
            const int row = equation[t[a]];
            if (row < 0)
                continue;
            for (int b = 0; b < 4; ++b)
            {
                const int col = equation[t[b]];
                if (col < 0)
                    rhs[row] -= ke(a, b) * exact(t[b]);
                else if (col <= row)
                    values[pattern.find(row, col)] += ke(a, b);
            }
        }
    }
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    solver.setPattern(n, pattern.tripletRows(), pattern.tripletColumns());
    solver.setValues(values);
    solver.solveSummedRhs(rhs);
    double worst = 0.0;
    for (int a = 0; a < numNodes; ++a)
        if (equation[a] >= 0)
            worst = std::max(worst, std::abs(rhs[equation[a]] - exact(a)));
    EXPECT_LT(worst, 1e-12) << "rank " << rank;
    EXPECT_EQ(solver.factorizationCount(), 1);
}

// P1 linear elasticity (E = 30 MPa, nu = 0.49), 3 dofs per node, assembled by element
// partitions. clamped: nodes on z = 0 fixed. Solves (or throws) and checks the residual
// with the distributed matrix (< 1e-10 relative).
namespace
{
void solveElasticity(bool clamped, std::vector<double>& rhsAndSolution, int& n)
{
    const TetMesh mesh = cubeTets(6);
    const int numNodes = static_cast<int>(mesh.x.size());
    std::vector<int> equation(3 * numNodes, -1);
    n = 0;
    for (int a = 0; a < numNodes; ++a)
        if (!clamped || mesh.x[a](2) > 1e-12)
            for (int d = 0; d < 3; ++d)
                equation[3 * a + d] = n++;
    const double e = 30e6, nu = 0.49;
    const double mu = e / (2 * (1 + nu)), lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
    Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
    d.topLeftCorner<3, 3>().setConstant(lambda);
    d.diagonal() << lambda + 2 * mu, lambda + 2 * mu, lambda + 2 * mu, mu, mu, mu;

    const std::vector<int> part = partitionElements(mesh.tets, commSize());
    std::vector<std::vector<int>> myDofs;
    std::vector<int> mine;
    for (std::size_t el = 0; el < mesh.tets.size(); ++el)
        if (part[el] == commRank())
        {
            mine.push_back(static_cast<int>(el));
            std::vector<int> dofs;
            for (int a : mesh.tets[el])
                for (int c = 0; c < 3; ++c)
                    dofs.push_back(equation[3 * a + c]);
            myDofs.push_back(dofs);
        }
    const CsrPattern pattern = CsrPattern::fromElements(n, myDofs, true);
    std::vector<double> values(pattern.nonZeros(), 0.0);
    for (std::size_t k = 0; k < mine.size(); ++k)
    {
        double volume = 0.0;
        const auto grad = gradients(mesh, mesh.tets[mine[k]], volume);
        Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
        for (int a = 0; a < 4; ++a)
        {
            const double gx = grad(a, 0), gy = grad(a, 1), gz = grad(a, 2);
            b(0, 3 * a) = gx;
            b(1, 3 * a + 1) = gy;
            b(2, 3 * a + 2) = gz;
            b(3, 3 * a) = gy, b(3, 3 * a + 1) = gx;     // xy
            b(4, 3 * a + 1) = gz, b(4, 3 * a + 2) = gy; // yz
            b(5, 3 * a) = gz, b(5, 3 * a + 2) = gx;     // xz
        }
        const Eigen::Matrix<double, 12, 12> ke = volume * b.transpose() * d * b;
        const auto& dofs = myDofs[k];
        for (int r = 0; r < 12; ++r)
            for (int c = 0; c < 12; ++c)
                if (dofs[r] >= 0 && dofs[c] >= 0 && dofs[c] <= dofs[r])
                    values[pattern.find(dofs[r], dofs[c])] += ke(r, c);
    }
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    solver.setPattern(n, pattern.tripletRows(), pattern.tripletColumns());
    solver.setValues(values);
    // a uniform load in -y on every free dof (rank 0 holds it all)
    rhsAndSolution.assign(n, 0.0);
    if (commRank() == 0)
        for (int i = 1; i < n; i += 3)
            rhsAndSolution[i] = -1.0;
    const std::vector<double> rhs = rhsAndSolution;
    solver.solveSummedRhs(rhsAndSolution);
    EXPECT_EQ(solver.negativePivotCount(), 0);
    // residual with the distributed (lower-triangle) matrix: sum of the ranks' K_local u
    const std::vector<int> rows = pattern.tripletRows();
    const std::vector<int>& cols = pattern.columns();
    std::vector<double> ku(n, 0.0), f = rhs;
    for (std::size_t k = 0; k < values.size(); ++k)
    {
        ku[rows[k]] += values[k] * rhsAndSolution[cols[k]];
        if (rows[k] != cols[k])
            ku[cols[k]] += values[k] * rhsAndSolution[rows[k]];
    }
    MPI_Allreduce(MPI_IN_PLACE, ku.data(), n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    MPI_Bcast(f.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    double r2 = 0.0, f2 = 0.0;
    for (int i = 0; i < n; ++i)
    {
        r2 += (ku[i] - f[i]) * (ku[i] - f[i]);
        f2 += f[i] * f[i];
    }
    EXPECT_LT(std::sqrt(r2 / f2), 1e-10) << "rank " << commRank();
}
} // namespace

TEST(DistributedAssembly, FloatingElasticBodyIsReportedSingular)
{
    std::vector<double> u;
    int n = 0;
    try
    {
        solveElasticity(false, u, n);
        FAIL() << "no exception for an unclamped body";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("check the clamped boundary"), std::string::npos)
            << e.what();
    }
}

TEST(DistributedAssembly, ClampedElasticBodySolves)
{
    std::vector<double> u;
    int n = 0;
    solveElasticity(true, u, n);
    ASSERT_EQ(static_cast<int>(u.size()), n);
    // loaded in -y: the mean y displacement is negative and everything is finite
    double mean = 0.0;
    for (int i = 1; i < n; i += 3)
        mean += u[i];
    EXPECT_LT(mean, 0.0);
    for (double v : u)
        EXPECT_TRUE(std::isfinite(v));
}
