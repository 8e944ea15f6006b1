// SPDX-License-Identifier: GPL-3.0-or-later
// The linear re-solve of a level (small strain, a law linear in the strain): a second solve at
// the same step with new interface loads is one back-substitution with the level's
// factorization and gives the same displacement as a fresh solve with those loads.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{
mesh::Mesh beam()
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.1, 0.1};
    spec.cells = {10, 2, 2};
    const std::string file = fsi::testing::makeBlockMesh(
        fsi::testing::tempFile("linear_update_beam.msh"), TestCell::Tet10, spec);
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

namespace
{
// max |a - b| / max |b| over the wetted displacement vectors
double relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
    return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

Eigen::VectorXd wettedDisplacement(const fe::StructuralSolver& solver)
{
    const auto u = solver.wettedNodeDisplacements();
    return Eigen::Map<const Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(u.size()));
}

// The response to a load change, by two full solves: S(F + W) - S(F) at level 1.
struct ResponseCase
{
    mesh::Mesh mesh = beam();
    std::unique_ptr<material::Material> law =
        material::makeMaterial(viscoelastic(), material::Kinematics::SmallStrain);
    fe::ProblemDefinition problem;
    ResponseCase(double refactorDrift)
    {
        problem.clamped = {"x0"};
        problem.wetted = "x1";
        problem.refactorShearDrift = refactorDrift;
    }
    // level 0 accepted, level 1 (dt 0.5 s) solved under F; the solver is left there
    void solveLevelOne(fe::StructuralSolver& solver, std::size_t n) const
    {
        ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
        solver.acceptLevel();
        ASSERT_TRUE(solver.solve({0.5, 0.5}, tipLoad(n, -11, 1)).converged);
    }
};

Eigen::MatrixXd loadChanges(std::size_t n)
{
    Eigen::MatrixXd w(3 * n, 2);
    const auto a = tipLoad(n, -2, 3), b = tipLoad(n, 1, 0);
    for (std::size_t i = 0; i < 3 * n; ++i)
    {
        w(static_cast<Eigen::Index>(i), 0) = a.forces[i];
        w(static_cast<Eigen::Index>(i), 1) = b.forces[i] * (1.0 + 0.1 * static_cast<double>(i % 7));
    }
    return w;
}
} // namespace

// interfaceResponse(W) = S(F + W) - S(F) (the solid is affine in its loads at a level), to the
// asked relative residual on a stale factorization (CG) and exactly on a current one; it changes
// nothing of the solver's state.
TEST(InterfaceResponse, EqualsTheDifferenceOfTwoSolves)
{
    for (const double drift : {0.0, 1e-6}) // 0: CG on the level-0 factor; 1e-6: refactorized
    {
        SCOPED_TRACE(drift == 0.0 ? "stale factorization (CG)" : "current factorization");
        const ResponseCase c(drift);
        fe::StructuralSolver solver(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
        const std::size_t n = solver.wettedNodes().size();
        c.solveLevelOne(solver, n);
        const Eigen::VectorXd base = wettedDisplacement(solver);
        const std::vector<double> before = solver.displacement();
        const Eigen::MatrixXd w = loadChanges(n);
        const int factorizations = solver.factorizationCount();

        const Eigen::MatrixXd loose = solver.interfaceResponse(w, 1e-2);
        const Eigen::MatrixXd tight = solver.interfaceResponse(w, 1e-9);
        EXPECT_EQ(solver.interfaceResponseColumns(), 4);
        EXPECT_EQ(solver.factorizationCount(), factorizations); // no refactorization for it
        EXPECT_EQ(solver.displacement(), before);               // state untouched (exact)

        for (Eigen::Index j = 0; j < w.cols(); ++j)
        {
            fe::InterfaceLoads shifted = tipLoad(n, -11, 1);
            for (std::size_t i = 0; i < 3 * n; ++i)
                shifted.forces[i] += w(static_cast<Eigen::Index>(i), j);
            fe::StructuralSolver reference(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
            c.solveLevelOne(reference, n);
            ASSERT_TRUE(reference.solve({0.5, 0.5}, shifted).converged);
            const Eigen::VectorXd exact = wettedDisplacement(reference) - base;
            EXPECT_LT(relativeDifference(tight.col(j), exact), 1e-6) << "column " << j;
            // a residual of 1e-2 |b| leaves an error of that order (the stale factor is a good
            // preconditioner); a current factor is exact
            EXPECT_LT(relativeDifference(loose.col(j), exact), drift == 0.0 ? 3e-2 : 1e-6)
                << "column " << j;
            std::printf("interface response, %s factor, column %d: error %.1e with 1e-2 "
                        "asked, %.1e with 1e-9\n",
                        drift == 0.0 ? "stale" : "current", static_cast<int>(j),
                        relativeDifference(loose.col(j), exact),
                        relativeDifference(tight.col(j), exact));
        }
        // the level's next solve is still the linear update of the last converged solve
        const auto again = solver.solve({0.5, 0.5}, tipLoad(n, -12, 3));
        ASSERT_TRUE(again.converged);
        EXPECT_NE(again.message.find("linear update"), std::string::npos) << again.message;
    }
}

TEST(InterfaceResponse, NeedsALinearProblemAndAConvergedSolve)
{
    const ResponseCase c(0.05);
    fe::StructuralSolver solver(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
    const std::size_t n = solver.wettedNodes().size();
    EXPECT_TRUE(solver.linearInLoads());
    EXPECT_THROW(solver.interfaceResponse(loadChanges(n), 1e-2), std::logic_error); // no solve
    ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
    EXPECT_THROW(solver.interfaceResponse(Eigen::MatrixXd::Zero(5, 1), 1e-2),
                 std::invalid_argument);
    EXPECT_THROW(solver.interfaceResponse(loadChanges(n), 0.0), std::invalid_argument);

    const auto law = material::makeMaterial(viscoelastic(), material::Kinematics::TotalLagrangian);
    fe::ProblemDefinition p = c.problem;
    p.kinematics = material::Kinematics::TotalLagrangian;
    fe::StructuralSolver finite(MPI_COMM_WORLD, c.mesh, *law, p);
    ASSERT_TRUE(finite.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
    EXPECT_FALSE(finite.linearInLoads());
    EXPECT_THROW(finite.interfaceResponse(loadChanges(n), 1e-2), std::logic_error);
}

// The level's earlier solves are reused: a re-solve whose load change lies in the span of the
// response columns' loads is found by projection, so CG on the stale factor needs fewer
// iterations than without those columns, and the answer is the same.
TEST(InterfaceResponse, LaterSolvesOfTheLevelStartFromItsEarlierOnes)
{
    const ResponseCase c(0.0); // CG on the level-0 factor throughout
    std::vector<double> displacement[2];
    int iterations[2] = {0, 0};
    for (const bool withColumns : {false, true})
    {
        fe::StructuralSolver solver(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
        const std::size_t n = solver.wettedNodes().size();
        c.solveLevelOne(solver, n);
        const Eigen::MatrixXd columns = loadChanges(n);
        if (withColumns)
            solver.interfaceResponse(columns, 1e-2);
        fe::InterfaceLoads next = tipLoad(n, -11, 1);
        for (std::size_t i = 0; i < 3 * n; ++i)
            next.forces[i] += 0.7 * columns(static_cast<Eigen::Index>(i), 0) -
                              0.2 * columns(static_cast<Eigen::Index>(i), 1);
        const int before = solver.linearSolver().reuseIterationCount();
        const auto report = solver.solve({0.5, 0.5}, next);
        ASSERT_TRUE(report.converged);
        EXPECT_NE(report.message.find("linear update"), std::string::npos) << report.message;
        iterations[withColumns] = solver.linearSolver().reuseIterationCount() - before;
        displacement[withColumns] = solver.displacement();
    }
    EXPECT_GE(iterations[0], 2);
    EXPECT_LT(iterations[1], iterations[0]);
    std::printf("re-solve on a stale factor: %d CG iterations without the level's earlier "
                "solves, %d with them\n",
                iterations[0], iterations[1]);
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < displacement[0].size(); ++i)
    {
        diff = std::max(diff, std::abs(displacement[1][i] - displacement[0][i]));
        scale = std::max(scale, std::abs(displacement[0][i]));
    }
    EXPECT_LT(diff, 1e-8 * scale);
}

// solveWithResponse = solve() then interfaceResponse(), in one lockstep linear solve: the same
// displacement and columns; on a stale factor fewer MUMPS solve phases in all, because the
// columns ride along with the Newton step's CG iterations instead of iterating on their own.
TEST(InterfaceResponse, SolveWithResponseEqualsSolveThenResponse)
{
    for (const double drift : {0.0, 1e-6}) // 0: CG on the level-0 factor; 1e-6: refactorized
    {
        SCOPED_TRACE(drift == 0.0 ? "stale factorization (CG)" : "current factorization");
        const ResponseCase c(drift);
        std::vector<double> displacement[2];
        Eigen::MatrixXd responses[2];
        int phases[2] = {0, 0}; // MUMPS solve phases
        for (const bool together : {false, true})
        {
            fe::StructuralSolver solver(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
            const std::size_t n = solver.wettedNodes().size();
            ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoad(n, -10, 0)).converged);
            solver.acceptLevel();
            const Eigen::MatrixXd w = loadChanges(n);
            const int before = solver.linearSolver().backSubstitutionCount();
            if (together)
            {
                ASSERT_TRUE(
                    solver.solveWithResponse({0.5, 0.5}, tipLoad(n, -11, 1), w, 1e-9, responses[1])
                        .converged);
            }
            else
            {
                ASSERT_TRUE(solver.solve({0.5, 0.5}, tipLoad(n, -11, 1)).converged);
                responses[0] = solver.interfaceResponse(w, 1e-9);
            }
            phases[together] = solver.linearSolver().backSubstitutionCount() - before;
            displacement[together] = solver.displacement();
            EXPECT_EQ(solver.interfaceResponseColumns(), 2);
            // the level goes on as after a solve(): its next solve is a linear update
            const auto again = solver.solve({0.5, 0.5}, tipLoad(n, -12, 3));
            ASSERT_TRUE(again.converged);
            EXPECT_NE(again.message.find("linear update"), std::string::npos) << again.message;
        }
        double diff = 0, scale = 0;
        for (std::size_t i = 0; i < displacement[0].size(); ++i)
        {
            diff = std::max(diff, std::abs(displacement[1][i] - displacement[0][i]));
            scale = std::max(scale, std::abs(displacement[0][i]));
        }
        EXPECT_LT(diff, 1e-8 * scale);
        ASSERT_EQ(responses[1].cols(), 2);
        for (Eigen::Index j = 0; j < 2; ++j)
            EXPECT_LT(relativeDifference(responses[1].col(j), responses[0].col(j)), 1e-6)
                << "column " << j;
        if (drift == 0.0)
        {
            EXPECT_LT(phases[1], phases[0]);
            std::printf("stale factor: %d MUMPS solve phases for the solve and then the columns, "
                        "%d with the columns riding along\n",
                        phases[0], phases[1]);
        }
    }
}

TEST(InterfaceResponse, SolveWithResponseChecksItsInputFirst)
{
    const ResponseCase c(0.05);
    fe::StructuralSolver solver(MPI_COMM_WORLD, c.mesh, *c.law, c.problem);
    const std::size_t n = solver.wettedNodes().size();
    Eigen::MatrixXd responses;
    EXPECT_THROW(solver.solveWithResponse({0.0, 0.0}, tipLoad(n, -10, 0),
                                          Eigen::MatrixXd::Zero(5, 1), 1e-2, responses),
                 std::invalid_argument);
    EXPECT_EQ(solver.factorizationCount(), 0); // nothing solved
    const auto law = material::makeMaterial(viscoelastic(), material::Kinematics::TotalLagrangian);
    fe::ProblemDefinition p = c.problem;
    p.kinematics = material::Kinematics::TotalLagrangian;
    fe::StructuralSolver finite(MPI_COMM_WORLD, c.mesh, *law, p);
    EXPECT_THROW(
        finite.solveWithResponse({0.0, 0.0}, tipLoad(n, -10, 0), loadChanges(n), 1e-2, responses),
        std::logic_error);
}
