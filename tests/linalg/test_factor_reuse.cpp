// SPDX-License-Identifier: GPL-3.0-or-later
// reuseFactorization: when the values of an SPD matrix change a little, the solve runs CG
// preconditioned by the old factorization (no new factorization) and still meets the
// tolerance; a large change falls back to a new factorization. Tridiagonal K(s) = K0 + s D
// with K0 the 1-D Dirichlet Laplacian and D the identity (a stiffness whose one part scales, as
// a viscoelastic tangent's deviatoric part does with dt). Any number of ranks (rows split).
#include "linalg/SparseDirectSolver.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace fsi::linalg;

namespace
{
constexpr int n = 400;

int rankOfWorld()
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

struct Matrix
{
    std::vector<int> rows, cols;
    std::vector<double> values;
};

// This rank's rows (i % size == rank), full symmetric storage.
Matrix matrix(double s)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    Matrix m;
    for (int i = rank; i < n; i += size)
    {
        m.rows.push_back(i), m.cols.push_back(i), m.values.push_back(2.0 + s);
        if (i > 0)
            m.rows.push_back(i), m.cols.push_back(i - 1), m.values.push_back(-1.0);
        if (i + 1 < n)
            m.rows.push_back(i), m.cols.push_back(i + 1), m.values.push_back(-1.0);
    }
    return m;
}

// max |K(s) x - b| / |b|_inf for the rank-0 solution x (checked on rank 0).
double residual(double s, const std::vector<double>& x, const std::vector<double>& b)
{
    double worst = 0.0, scale = 0.0;
    for (int i = 0; i < n; ++i)
    {
        double y = (2.0 + s) * x[i];
        if (i > 0)
            y -= x[i - 1];
        if (i + 1 < n)
            y -= x[i + 1];
        worst = std::max(worst, std::abs(y - b[i]));
        scale = std::max(scale, std::abs(b[i]));
    }
    return worst / scale;
}
} // namespace

TEST(FactorReuse, SmallChangeSolvesByCgOnTheOldFactor)
{
    DirectSolverOptions options;
    options.reuseFactorization = true;
    SparseDirectSolver solver(MPI_COMM_WORLD, options);
    const double s0 = 0.1;
    Matrix m = matrix(s0);
    solver.setPattern(n, m.rows, m.cols);
    solver.setValues(m.values);
    std::vector<double> b(n);
    for (int i = 0; i < n; ++i)
        b[i] = std::sin(0.05 * i) + 1.0;
    std::vector<double> x = b;
    solver.solve(x);
    EXPECT_EQ(solver.factorizationCount(), 1);
    if (rankOfWorld() == 0)
    {
        EXPECT_LT(residual(s0, x, b), 1e-12);
    }

    // s changes by 5 %: CG on the old factor, a handful of iterations, no new factorization
    const double s1 = 0.105;
    solver.setValues(matrix(s1).values);
    x = b;
    solver.solve(x);
    EXPECT_EQ(solver.factorizationCount(), 1);
    EXPECT_EQ(solver.reusedSolveCount(), 1);
    EXPECT_LE(solver.reuseIterationCount(), 6);
    if (rankOfWorld() == 0)
    {
        EXPECT_LT(residual(s1, x, b), 1e-9);
    }

    // s x 100: CG on the stale factor does not meet the tolerance in time -> factorize
    const double s2 = 10.0;
    solver.setValues(matrix(s2).values);
    x = b;
    solver.solve(x);
    EXPECT_EQ(solver.factorizationCount(), 2);
    if (rankOfWorld() == 0)
    {
        EXPECT_LT(residual(s2, x, b), 1e-12);
    }
}

TEST(FactorReuse, OffByDefault)
{
    SparseDirectSolver solver(MPI_COMM_WORLD);
    Matrix m = matrix(0.1);
    solver.setPattern(n, m.rows, m.cols);
    solver.setValues(m.values);
    std::vector<double> x(n, 1.0);
    solver.solve(x);
    solver.setValues(matrix(0.105).values);
    x.assign(n, 1.0);
    solver.solve(x);
    EXPECT_EQ(solver.factorizationCount(), 2);
    EXPECT_EQ(solver.reusedSolveCount(), 0);
}

// A right-hand side of zero on a stale factor: x = 0, no factorization (it used to factorize).
TEST(FactorReuse, ZeroRightHandSideNeedsNoFactorization)
{
    DirectSolverOptions options;
    options.reuseFactorization = true;
    SparseDirectSolver solver(MPI_COMM_WORLD, options);
    Matrix m = matrix(0.1);
    solver.setPattern(n, m.rows, m.cols);
    solver.setValues(m.values);
    std::vector<double> x(n, 1.0);
    solver.solve(x);
    solver.setValues(matrix(0.105).values);
    x.assign(n, 0.0);
    solver.solve(x);
    EXPECT_EQ(solver.factorizationCount(), 1);
    if (rankOfWorld() == 0)
    {
        for (double v : x)
            ASSERT_EQ(v, 0.0);
    }
}

// residualAllowance: CG on the stale factor stops once |b - A x| <= allowance (fewer
// iterations than for 1e-10 |b|) and meets it; a current factor ignores it.
TEST(FactorReuse, ResidualAllowanceStopsCgEarlier)
{
    DirectSolverOptions options;
    options.reuseFactorization = true;
    options.refactorAfterIterations = 100; // keep the stale factor for both solves
    SparseDirectSolver solver(MPI_COMM_WORLD, options);
    Matrix m = matrix(0.1);
    solver.setPattern(n, m.rows, m.cols);
    solver.setValues(m.values);
    std::vector<double> b(n), x;
    double bNorm = 0.0;
    for (int i = 0; i < n; ++i)
    {
        b[i] = std::sin(0.05 * i) + 1.0;
        bNorm += b[i] * b[i];
    }
    bNorm = std::sqrt(bNorm);
    x = b;
    solver.solve(x);
    const double s1 = 0.3; // three times stiffer diagonal shift: several CG iterations
    solver.setValues(matrix(s1).values);
    x = b;
    solver.solve(x);
    const int tight = solver.reuseIterationCount();
    x = b;
    solver.solve(x, 1e-4 * bNorm);
    const int loose = solver.reuseIterationCount() - tight;
    EXPECT_EQ(solver.factorizationCount(), 1);
    EXPECT_EQ(solver.reusedSolveCount(), 2);
    EXPECT_LT(loose, tight);
    EXPECT_GE(loose, 1);
    if (rankOfWorld() == 0)
    {
        double r2 = 0.0; // |b - A x|_2
        for (int i = 0; i < n; ++i)
        {
            double y = (2.0 + s1) * x[i] - (i > 0 ? x[i - 1] : 0.0) - (i + 1 < n ? x[i + 1] : 0.0);
            r2 += (y - b[i]) * (y - b[i]);
        }
        EXPECT_LE(std::sqrt(r2), 1e-4 * bNorm);
        EXPECT_GT(std::sqrt(r2), 1e-10 * bNorm); // it did stop early
    }
}

// solveMany: three right-hand sides (one of them zero) give the same solutions as solve() one
// by one, on a current factor (one solve phase for all) and on a stale one (CG in lockstep: one
// solve phase per iteration for the unfinished columns, the same iteration counts).
TEST(FactorReuse, SolveManyEqualsColumnByColumn)
{
    DirectSolverOptions options;
    options.reuseFactorization = true;
    options.refactorAfterIterations = 100;
    SparseDirectSolver many(MPI_COMM_WORLD, options), single(MPI_COMM_WORLD, options);
    for (SparseDirectSolver* s : {&many, &single})
    {
        Matrix m = matrix(0.1);
        s->setPattern(n, m.rows, m.cols);
        s->setValues(m.values);
    }
    constexpr int k = 3;
    std::vector<double> b(static_cast<std::size_t>(n) * k, 0.0);
    for (int i = 0; i < n; ++i)
    {
        b[i] = std::sin(0.05 * i) + 1.0;
        b[n + i] = std::cos(0.3 * i);
        // column 2 stays zero
    }
    const std::vector<double> allowances = {0.0, 1e-6, 0.0};
    for (const double s : {0.1, 0.3}) // current factor, then stale (3x stiffer diagonal shift)
    {
        SCOPED_TRACE(s == 0.1 ? "current factor" : "stale factor");
        many.setValues(matrix(s).values);
        single.setValues(matrix(s).values);
        const int phases = many.backSubstitutionCount();
        std::vector<double> x = b;
        many.solveMany(x, k, allowances);
        std::vector<int> iterations;
        for (int j = 0; j < k; ++j)
        {
            std::vector<double> column(b.begin() + j * n, b.begin() + (j + 1) * n);
            const int before = single.reuseIterationCount();
            single.solve(column, allowances[j]);
            iterations.push_back(single.reuseIterationCount() - before);
            if (rankOfWorld() == 0)
            {
                for (int i = 0; i < n; ++i)
                    ASSERT_NEAR(x[j * n + i], column[i], 1e-12 * (1.0 + std::abs(column[i])))
                        << "column " << j << " row " << i;
            }
        }
        EXPECT_EQ(many.factorizationCount(), 1);
        if (s == 0.1)
        {
            EXPECT_EQ(many.backSubstitutionCount() - phases, 1); // all columns in one phase
        }
        else
        {
            // lockstep: one phase to start plus one per iteration of the slowest column
            const int slowest = *std::max_element(iterations.begin(), iterations.end());
            EXPECT_GE(slowest, 2);
            EXPECT_EQ(many.backSubstitutionCount() - phases, slowest);
            EXPECT_EQ(many.reuseIterationCount(), iterations[0] + iterations[1] + iterations[2]);
        }
    }
}
