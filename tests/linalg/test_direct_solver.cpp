// SPDX-License-Identifier: GPL-3.0-or-later
// SparseDirectSolver on a manufactured 3-D Laplacian (7-point stencil, Dirichlet boundary
// eliminated). Runs on any number of ranks: each rank passes a share of the triplets, and
// the diagonal is split into two duplicates held by different ranks (summed by MUMPS).
#include "linalg/SparseDirectSolver.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>
#include <tuple>

using namespace fsi::linalg;

namespace
{
int rank()
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int ranks()
{
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}

struct Triplets
{
    std::vector<int> rows, cols;
    std::vector<double> values;
    void add(int r, int c, double v)
    {
        rows.push_back(r);
        cols.push_back(c);
        values.push_back(v);
    }
};

// m^3 interior points; full (both triangles) 7-point Laplacian. Row i belongs to rank
// i % size; its diagonal is 2 (owner) + diagonalRest (next rank). convection adds an
// unsymmetric +c on (i, i+1) in x. neumann: diagonal = number of neighbours (singular).
struct Laplacian
{
    int m;
    double convection = 0.0;
    bool neumann = false;
    int size() const { return m * m * m; }
    int index(int i, int j, int k) const { return i + m * (j + m * k); }

    template <class F> void forEachEntry(F&& visit) const
    {
        for (int k = 0; k < m; ++k)
            for (int j = 0; j < m; ++j)
                for (int i = 0; i < m; ++i)
                {
                    const int row = index(i, j, k);
                    int neighbours = 0;
                    const int di[6] = {-1, 1, 0, 0, 0, 0}, dj[6] = {0, 0, -1, 1, 0, 0},
                              dk[6] = {0, 0, 0, 0, -1, 1};
                    for (int n = 0; n < 6; ++n)
                    {
                        const int a = i + di[n], b = j + dj[n], c = k + dk[n];
                        if (a < 0 || b < 0 || c < 0 || a >= m || b >= m || c >= m)
                            continue;
                        ++neighbours;
                        visit(row, index(a, b, c), -1.0 + (n == 1 ? convection : 0.0));
                    }
                    visit(row, row, neumann ? double(neighbours) : 6.0);
                }
    }

    Triplets localTriplets(int r, int s) const
    {
        Triplets t;
        forEachEntry(
            [&](int row, int col, double v)
            {
                if (row != col)
                {
                    if (row % s == r)
                        t.add(row, col, v);
                }
                else
                {
                    if (row % s == r)
                        t.add(row, col, 2.0);
                    if (row % s == (r + s - 1) % s) // the next rank holds the rest
                        t.add(row, col, v - 2.0);
                }
            });
        return t;
    }

    std::vector<double> multiply(const std::vector<double>& x) const
    {
        std::vector<double> y(size(), 0.0);
        forEachEntry([&](int row, int col, double v) { y[row] += v * x[col]; });
        return y;
    }
};

std::vector<double> manufactured(int n)
{
    std::vector<double> x(n);
    for (int i = 0; i < n; ++i)
        x[i] = 1.0 + std::sin(0.1 * i) + 0.01 * i;
    return x;
}

double norm(const std::vector<double>& v)
{
    double s = 0.0;
    for (double x : v)
        s += x * x;
    return std::sqrt(s);
}

double relativeResidual(const Laplacian& a, const std::vector<double>& x,
                        const std::vector<double>& b)
{
    std::vector<double> r = a.multiply(x);
    for (std::size_t i = 0; i < r.size(); ++i)
        r[i] -= b[i];
    return norm(r) / norm(b);
}

void load(SparseDirectSolver& solver, const Laplacian& a)
{
    Triplets t = a.localTriplets(rank(), ranks());
    solver.setPattern(a.size(), t.rows, t.cols);
    solver.setValues(t.values);
}
} // namespace

using Case = std::tuple<bool, bool, Ordering>; // symmetric, positiveDefinite, ordering

class DirectSolve : public ::testing::TestWithParam<Case>
{
};

TEST_P(DirectSolve, ManufacturedLaplacian)
{
    const auto [symmetric, spd, ordering] = GetParam();
    DirectSolverOptions options;
    options.symmetric = symmetric;
    options.positiveDefinite = spd;
    options.ordering = static_cast<int>(ordering);
    Laplacian a{14, symmetric ? 0.0 : 0.4};
    SparseDirectSolver solver(MPI_COMM_WORLD, options);
    load(solver, a);
    const std::vector<double> exact = manufactured(a.size());
    const std::vector<double> b = a.multiply(exact);
    std::vector<double> x = rank() == 0 ? b : std::vector<double>{};
    solver.solve(x);
    if (rank() == 0)
    {
        EXPECT_LT(relativeResidual(a, x, b), 1e-10);
        std::vector<double> error(x.size());
        for (std::size_t i = 0; i < x.size(); ++i)
            error[i] = x[i] - exact[i];
        EXPECT_LT(norm(error) / norm(exact), 1e-9);
    }
    else
    {
        EXPECT_TRUE(x.empty()); // centralized: other ranks untouched
    }
    EXPECT_EQ(solver.analysisCount(), 1);
    EXPECT_EQ(solver.factorizationCount(), 1);
    EXPECT_EQ(solver.solveCount(), 1);
    if (symmetric)
    {
        EXPECT_EQ(solver.negativePivotCount(), 0);
    }
    EXPECT_GT(solver.factorEntryCount(), a.size());
}

INSTANTIATE_TEST_SUITE_P(Options, DirectSolve,
                         ::testing::Values(Case{true, true, Ordering::Metis},
                                           Case{true, false, Ordering::Metis},
                                           Case{true, false, Ordering::Amd},
                                           Case{true, true, Ordering::Pord},
                                           Case{false, false, Ordering::Metis}));

TEST(DirectSolver, ReusesFactorizationWhenValuesAreUnchanged)
{
    Laplacian a{8};
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    load(solver, a);
    for (int k = 1; k <= 3; ++k)
    {
        std::vector<double> exact(a.size(), double(k)), b = a.multiply(exact);
        std::vector<double> x = b;
        load(solver, a); // same pattern, same values: nothing to redo
        solver.solve(x);
        if (rank() == 0)
        {
            EXPECT_LT(relativeResidual(a, x, b), 1e-10);
        }
    }
    EXPECT_EQ(solver.analysisCount(), 1);
    EXPECT_EQ(solver.factorizationCount(), 1);
    EXPECT_EQ(solver.solveCount(), 3);
    solver.factorize();
    EXPECT_EQ(solver.factorizationCount(), 1);

    // changed values (on rank 0 only): refactor everywhere, no new analysis
    Laplacian shifted{8};
    Triplets t = shifted.localTriplets(rank(), ranks());
    if (rank() == 0) // a diagonal entry (upper-triangle entries are ignored when symmetric)
    {
        std::size_t k = 0;
        while (t.rows[k] != t.cols[k])
            ++k;
        t.values[k] += 1e-3;
    }
    solver.setValues(t.values);
    std::vector<double> x(a.size(), 1.0);
    solver.solve(x);
    EXPECT_EQ(solver.analysisCount(), 1);
    EXPECT_EQ(solver.factorizationCount(), 2);

    // new pattern: new analysis
    Laplacian bigger{9};
    load(solver, bigger);
    std::vector<double> y(bigger.size(), 1.0);
    solver.solve(y);
    EXPECT_EQ(solver.analysisCount(), 2);
    EXPECT_EQ(solver.factorizationCount(), 3);
}

TEST(DirectSolver, SummedRhsGivesTheSolutionOnEveryRank)
{
    Laplacian a{10};
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    load(solver, a);
    const std::vector<double> exact = manufactured(a.size());
    const std::vector<double> b = a.multiply(exact);
    std::vector<double> x(b.size());
    for (std::size_t i = 0; i < b.size(); ++i)
        x[i] = b[i] / ranks(); // each rank holds a share
    solver.solveSummedRhs(x);
    EXPECT_LT(relativeResidual(a, x, b), 1e-10) << "rank " << rank();
}

// Default mode (general symmetric, null-pivot detection). With positiveDefinite = true MUMPS
// has no null-pivot detection: only an exactly zero or negative pivot is caught.
TEST(DirectSolver, NeumannLaplacianNamesTheClampedBoundary)
{
    DirectSolverOptions options;
    Laplacian a{6, 0.0, true}; // no Dirichlet: constant null space (a floating body)
    SparseDirectSolver solver(MPI_COMM_WORLD, options);
    load(solver, a);
    std::vector<double> x(a.size(), 1.0);
    try
    {
        solver.solve(x);
        FAIL() << "no exception for a singular matrix";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("check the clamped boundary"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(solver.factorizationCount(), 0);
}

TEST(DirectSolver, ZeroRowIsSingular)
{
    // 3 x 3 with an empty last row and column
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    std::vector<int> rows, cols;
    std::vector<double> values;
    if (rank() == 0)
    {
        rows = {0, 1, 1, 0, 2};
        cols = {0, 1, 0, 1, 2};
        values = {2.0, 2.0, -1.0, -1.0, 0.0};
    }
    solver.setPattern(3, rows, cols);
    solver.setValues(values);
    EXPECT_THROW(solver.factorize(), std::runtime_error);
}

TEST(DirectSolver, RejectsIndicesOutsideTheMatrix)
{
    SparseDirectSolver solver(MPI_COMM_WORLD, {});
    EXPECT_THROW(solver.setPattern(3, {0, 3}, {0, 0}), std::invalid_argument);
    EXPECT_THROW(solver.setPattern(3, {0, 1}, {0}), std::invalid_argument);
}
