// SPDX-License-Identifier: GPL-3.0-or-later
// The assembler's path end to end: METIS element partition -> each rank builds the CSR
// pattern of ITS elements (lower triangle) and assembles them -> SparseDirectSolver with
// duplicates summed across ranks -> solveSummedRhs. P1 tetrahedra for the Laplacian with
// a linear Dirichlet field reproduce it exactly (patch test), on any number of ranks.
#include "linalg/CsrPattern.hpp"
#include "linalg/Partition.hpp"
#include "linalg/SparseDirectSolver.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

using namespace fsi::linalg;

TEST(DistributedAssembly, LinearFieldIsReproducedExactly)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);

    // m^3 cubes on [0,1]^3, 6 tets each (Kuhn), slightly distorted interior nodes
    const int m = 8, nodesPerSide = m + 1;
    const int numNodes = nodesPerSide * nodesPerSide * nodesPerSide;
    auto node = [&](int i, int j, int k) { return i + nodesPerSide * (j + nodesPerSide * k); };
    std::vector<Eigen::Vector3d> x(numNodes);
    std::vector<bool> boundary(numNodes);
    for (int k = 0; k <= m; ++k)
        for (int j = 0; j <= m; ++j)
            for (int i = 0; i <= m; ++i)
            {
                const bool b = i == 0 || j == 0 || k == 0 || i == m || j == m || k == m;
                const double shift = b ? 0.0 : 0.15 / m * std::sin(i + 2.0 * j + 3.0 * k);
                x[node(i, j, k)] = Eigen::Vector3d(i, j, k) / m + Eigen::Vector3d::Constant(shift);
                boundary[node(i, j, k)] = b;
            }
    std::vector<std::vector<int>> tets;
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i)
            {
                const int v[8] = {node(i, j, k),
                                  node(i + 1, j, k),
                                  node(i + 1, j + 1, k),
                                  node(i, j + 1, k),
                                  node(i, j, k + 1),
                                  node(i + 1, j, k + 1),
                                  node(i + 1, j + 1, k + 1),
                                  node(i, j + 1, k + 1)};
                const int paths[6][2] = {{1, 2}, {1, 5}, {3, 2}, {3, 7}, {4, 5}, {4, 7}};
                for (const auto& p : paths)
                    tets.push_back({v[0], v[p[0]], v[p[1]], v[6]});
            }
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
        Eigen::Matrix3d jacobian;
        for (int c = 0; c < 3; ++c)
            jacobian.col(c) = x[t[c + 1]] - x[t[0]];
        const double volume = std::abs(jacobian.determinant()) / 6.0;
        Eigen::Matrix<double, 4, 3> grad;
        grad.bottomRows<3>() = jacobian.inverse();
        grad.row(0) = -grad.bottomRows<3>().colwise().sum();
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
