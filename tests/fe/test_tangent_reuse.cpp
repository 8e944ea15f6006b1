// SPDX-License-Identifier: GPL-3.0-or-later
// The cheap path of a linear level (small strain, viscoelastic): the tangent from its two
// isotropic parts (no cell loop after the first level), CG on the last factorization to a tenth
// of Newton's tolerance, a refactorization when the shear modulus drifted by more than 5 %, and
// re-solves with new loads only as one linear solve. Reference: the same law seen as nonlinear
// (NonlinearView), which takes the full path -- cell tangents at every level, Newton, a fresh
// factorization whenever the tangent changes.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"
#include "NonlinearView.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{
using fsi::testing::NonlinearView;

const mesh::Mesh& beam(TestCell cell)
{
    static std::map<TestCell, mesh::Mesh> meshes;
    auto it = meshes.find(cell);
    if (it == meshes.end())
    {
        fsi::testing::BlockSpec spec;
        spec.size = {1.0, 0.1, 0.1};
        spec.cells = {10, 2, 2};
        const std::string file = fsi::testing::makeBlockMesh(
            fsi::testing::tempFile("tangent_reuse_beam.msh"), cell, spec);
        it = meshes.emplace(cell, mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true)).first;
    }
    return it->second;
}

// G(dt) = G (1 + 0.3 g(dt / 1 s) + 0.2 g(dt / 20 s)), g(x) = (1 - e^-x) / x: 1.5 G at dt = 0.
material::MaterialParameters prony()
{
    return fsi::testing::viscoelasticKG(5e7, 1e7, {0.3, 0.2}, {1.0, 20.0});
}

// Levels [s] and the shear modulus drift from the factorized one (see prony()):
// 0 | 0.01 (-0.1 %: CG) | 0.51 (-4.3 %: CG) | 3.51 (-11 %: refactorize) | 6.71 (-0.5 %: CG) |
// 46.71 (-14 %: refactorize)
const std::vector<double> times{0.0, 0.01, 0.51, 3.51, 6.71, 46.71};

// Tip loads of coupling iteration k of level L [N]: lift and drag with a twist, changing from
// iteration to iteration by ~`change` (relative).
fe::InterfaceLoads tipLoads(const fe::StructuralSolver& solver, int L, int k, double change)
{
    const auto x = solver.wettedNodeCoordinates();
    const std::size_t n = x.size() / 3;
    fe::InterfaceLoads loads;
    loads.forces.assign(3 * n, 0.0);
    const double scale = 1.0 - 0.05 * L + change * k;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double twist = (x[3 * i + 2] - 0.05) / 0.05; // -1 .. 1 across z
        loads.forces[3 * i] = 2.0 * scale / n;
        loads.forces[3 * i + 1] = -(10.0 + 4.0 * twist * (1.0 + change * k)) * scale / n;
    }
    return loads;
}

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b)
{
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        diff = std::max(diff, std::abs(a[i] - b[i]));
        scale = std::max(scale, std::abs(b[i]));
    }
    return diff / scale;
}

// refactorized at a shear-modulus drift of 5 % (the default is never: RecycledSolutions below)
fe::ProblemDefinition cantilever(fe::Formulation formulation = fe::Formulation::Displacement)
{
    fe::ProblemDefinition p;
    p.formulation = formulation;
    p.clamped = {"x0"};
    p.wetted = "x1";
    p.refactorShearDrift = 0.05;
    return p;
}

// Every coupling iteration of every level, cheap path against the full path: the largest
// relative displacement difference.
double historyDifference(TestCell cell, fe::Formulation formulation, int& factorizations,
                         int& cellTangents, const fe::ProblemDefinition* cheapProblem = nullptr,
                         int* cgIterations = nullptr)
{
    const auto law = material::makeMaterial(prony(), material::Kinematics::SmallStrain);
    const NonlinearView full(*law);
    const mesh::Mesh& m = beam(cell);
    fe::StructuralSolver cheap(MPI_COMM_WORLD, m, *law,
                               cheapProblem ? *cheapProblem : cantilever(formulation));
    fe::StructuralSolver reference(MPI_COMM_WORLD, m, full, cantilever(formulation));
    double worst = 0.0;
    for (std::size_t L = 0; L < times.size(); ++L)
    {
        const material::TimeStep step{times[L], L == 0 ? 0.0 : times[L] - times[L - 1]};
        for (int k = 0; k < 3; ++k)
        {
            const auto a = cheap.solve(step, tipLoads(cheap, L, k, 0.02));
            const auto b = reference.solve(step, tipLoads(reference, L, k, 0.02));
            EXPECT_TRUE(a.converged && b.converged) << a.message << " / " << b.message;
            worst =
                std::max(worst, relativeDifference(cheap.displacement(), reference.displacement()));
        }
        cheap.acceptLevel();
        reference.acceptLevel();
    }
    EXPECT_EQ(reference.factorizationCount(), static_cast<int>(times.size())); // fresh per dt
    factorizations = cheap.factorizationCount();
    cellTangents = cheap.elementTangentAssemblyCount();
    if (cgIterations)
        *cgIterations = cheap.linearSolver().reuseIterationCount();
    return worst;
}
} // namespace

// The whole history -- dt changes (CG on an older factorization, refactorizations) and
// re-solves with new loads -- gives the displacements of fresh factorizations to 1e-10
// relative (the cheap path stops at a tenth of Newton's 1e-8 force tolerance). A tangent reused
// without CG after a dt change would be off by the drift of the shear modulus (0.1-14 %).
TEST(TangentReuse, HistoryMatchesFreshFactorizations)
{
    int factorizations = 0, cellTangents = 0;
    const double worst = historyDifference(TestCell::Tet10, fe::Formulation::Displacement,
                                           factorizations, cellTangents);
    std::printf("Tet10: largest relative displacement difference %.2e, %d factorizations\n", worst,
                factorizations);
    EXPECT_LT(worst, 1e-10);
    EXPECT_EQ(factorizations, 3); // dt = 0, and the two drifts above 5 %
    EXPECT_EQ(cellTangents, 2);   // the lambda and mu parts, once
}

// Never refactorized (the default): CG on the level-0 factor through a 39 % drop of the shear
// modulus, each solve first projected on the kept solutions of every earlier level. Both with
// and without that recycling the history equals fresh factorizations to 1e-10; recycling needs
// fewer CG iterations (counts, not time).
TEST(TangentReuse, RecycledSolutionsServeLaterLevels)
{
    int iterations[2] = {0, 0};
    for (const bool recycle : {false, true})
    {
        SCOPED_TRACE(recycle ? "recycled across levels" : "kept for the level only");
        fe::ProblemDefinition problem = cantilever();
        problem.refactorShearDrift = 0.0;
        problem.recycleSolutions = recycle;
        int factorizations = 0, cellTangents = 0;
        const double worst =
            historyDifference(TestCell::Tet10, fe::Formulation::Displacement, factorizations,
                              cellTangents, &problem, &iterations[recycle ? 1 : 0]);
        EXPECT_LT(worst, 1e-10);
        EXPECT_EQ(factorizations, 1); // dt = 0 only
    }
    std::printf("CG iterations over the history: %d kept for the level, %d recycled\n",
                iterations[0], iterations[1]);
    EXPECT_LT(iterations[1], iterations[0]);
}

// The same with B-bar hexahedra (the projected dilatation is linear in the strain too).
TEST(TangentReuse, ProjectedDilatationHexahedraMatchFreshFactorizations)
{
    int factorizations = 0, cellTangents = 0;
    const double worst = historyDifference(TestCell::Hex8, fe::Formulation::ProjectedDilatation,
                                           factorizations, cellTangents);
    EXPECT_LT(worst, 1e-10);
    EXPECT_EQ(factorizations, 3);
    EXPECT_EQ(cellTangents, 2);
}

// Cost in linear-solver operations (counts, not time): a re-solve of a level with loads
// changed by 1e-3 needs at most 2 CG iterations on the factorization of a tangent 0.1 % away,
// and none after the level's own refactorization (one back-substitution).
TEST(TangentReuse, ReSolvesOfALevelCostFewBackSubstitutions)
{
    const auto law = material::makeMaterial(prony(), material::Kinematics::SmallStrain);
    fe::StructuralSolver solver(MPI_COMM_WORLD, beam(TestCell::Tet10), *law, cantilever());
    const auto& linear = solver.linearSolver();
    ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoads(solver, 0, 0, 1e-3)).converged);
    solver.acceptLevel();
    // level 1: dt = 0.01 s, the shear modulus 0.1 % below the factorized one
    ASSERT_TRUE(solver.solve({0.01, 0.01}, tipLoads(solver, 1, 0, 1e-3)).converged);
    for (int k = 1; k <= 3; ++k)
    {
        const int cg = linear.reuseIterationCount();
        const auto r = solver.solve({0.01, 0.01}, tipLoads(solver, 1, k, 1e-3));
        ASSERT_TRUE(r.converged);
        EXPECT_NE(r.message.find("linear update"), std::string::npos) << r.message;
        EXPECT_LE(linear.reuseIterationCount() - cg, 2) << "re-solve " << k;
    }
    EXPECT_EQ(solver.factorizationCount(), 1);
    solver.acceptLevel();
    // level 2: dt = 3 s, the shear modulus 17 % below: refactorized at the level's first solve
    ASSERT_TRUE(solver.solve({3.01, 3.0}, tipLoads(solver, 2, 0, 1e-3)).converged);
    EXPECT_EQ(solver.factorizationCount(), 2);
    for (int k = 1; k <= 3; ++k)
    {
        const int reused = linear.reusedSolveCount(), back = linear.backSubstitutionCount();
        ASSERT_TRUE(solver.solve({3.01, 3.0}, tipLoads(solver, 2, k, 1e-3)).converged);
        EXPECT_EQ(linear.reusedSolveCount(), reused);
        EXPECT_EQ(linear.backSubstitutionCount() - back, 1);
    }
    EXPECT_EQ(solver.factorizationCount(), 2);
    EXPECT_EQ(solver.elementTangentAssemblyCount(), 2);
}

// A re-solve with the very loads of the last solve changes nothing and factorizes nothing.
TEST(TangentReuse, ReSolveWithUnchangedLoadsKeepsTheState)
{
    const auto law = material::makeMaterial(prony(), material::Kinematics::SmallStrain);
    fe::StructuralSolver solver(MPI_COMM_WORLD, beam(TestCell::Tet10), *law, cantilever());
    ASSERT_TRUE(solver.solve({0.0, 0.0}, tipLoads(solver, 0, 0, 0.0)).converged);
    solver.acceptLevel();
    ASSERT_TRUE(solver.solve({0.01, 0.01}, tipLoads(solver, 1, 0, 0.0)).converged);
    const auto u = solver.displacement();
    const auto again = solver.solve({0.01, 0.01}, tipLoads(solver, 1, 0, 0.0));
    ASSERT_TRUE(again.converged);
    EXPECT_EQ(solver.factorizationCount(), 1);
    EXPECT_LT(relativeDifference(solver.displacement(), u), 1e-12);
}
