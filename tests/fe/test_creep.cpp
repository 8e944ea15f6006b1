// SPDX-License-Identifier: GPL-3.0-or-later
// Viscoelastic structural check: a cube under a uniaxial step stress held constant creeps as
// eps(t) = sigma0 [1/(9K) + J(t)/3], J the shear creep compliance of reference/prony.md
// (K = 10 MPa elastic, G0 = 1 MPa, Abaqus g = (0.3, 0.2), tau = (0.1, 10) s):
//   J(t) = 2e-6 - 4.2504e-7 e^{-t/0.142681} - 5.7496e-7 e^{-t/14.0173}  [1/Pa].
// Also: re-solving a level leaves the history untouched; the factorization is reused for
// every level with the same dt (small strain, constant tangent per dt).
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace fsi;

namespace
{
double creepCompliance(double t)
{
    return 2e-6 - 4.2504e-7 * std::exp(-t / 0.142681) - 5.7496e-7 * std::exp(-t / 14.0173);
}
// A viscoelastic law: Abaqus g_i and tau_i [s] on G0 = 1 MPa (instantaneous), K = 10 MPa.
std::unique_ptr<material::Material> viscoelasticLaw(const std::vector<double>& g,
                                                    const std::vector<double>& tau,
                                                    const std::string& integration = "")
{
    material::MaterialParameters mp;
    mp.type = "viscoelastic";
    mp.bulkModulus = 10e6;
    mp.shearModulus = 1e6;
    mp.modulusBasis = "instantaneous";
    mp.pronyConvention = "abaqus-g";
    mp.pronyCoefficients = g;
    mp.pronyTimes = tau;
    mp.pronyIntegration = integration;
    return material::makeMaterial(mp, material::Kinematics::SmallStrain);
}

// The unit cube on rollers at x0, y0, z0 under a uniaxial traction sigma0 [Pa] on x1.
fe::ProblemDefinition uniaxialTraction(double sigma0)
{
    fe::ProblemDefinition p;
    for (int c = 0; c < 3; ++c)
    {
        fe::PrescribedDisplacement d;
        d.surface = std::string(1, "xyz"[c]) + "0";
        d.value[c] = 0.0;
        p.displacements.push_back(d);
    }
    p.tractions.push_back({"x1", Eigen::Vector3d(sigma0, 0, 0)});
    p.newton.residualTolerance = 1e-12;
    return p;
}
} // namespace

TEST(Viscoelastic, UniaxialCreepMatchesAnalyticCompliance)
{
    fsi::testing::BlockSpec spec;
    spec.cells = {2, 2, 2};
    const auto file = fsi::testing::makeBlockMesh(fsi::testing::tempFile("creep.msh"),
                                                  fsi::testing::TestCell::Tet10, spec);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "y0", "z0", "x1"}}, true);
    const auto law = viscoelasticLaw({0.3, 0.2}, {0.1, 10.0});
    const double K = 10e6, sigma0 = 1e4;
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, uniaxialTraction(sigma0));
    const int probe = m.nearestNode(Eigen::Vector3d(1, 0.5, 0.5));

    // time grid: dt = 0.005 to 1 s, 0.05 to 10 s, 1 s to 100 s
    std::vector<double> times{0.0}, steps{0.0}; // nominal dt per level (bitwise constant)
    for (int i = 1; i <= 200; ++i)
        times.push_back(0.005 * i), steps.push_back(0.005);
    for (int i = 1; i <= 180; ++i)
        times.push_back(1.0 + 0.05 * i), steps.push_back(0.05);
    for (int i = 1; i <= 90; ++i)
        times.push_back(10.0 + 1.0 * i), steps.push_back(1.0);
    double maxError = 0.0;
    std::printf("  t [s]    eps_xx (FE)      eps_xx (analytic)   rel. error\n");
    for (std::size_t n = 0; n < times.size(); ++n)
    {
        const material::TimeStep step{times[n], steps[n]};
        auto r = solver.solve(step);
        ASSERT_TRUE(r.converged) << r.message;
        if (n == 250)
        { // re-solve the same level: same answer, history untouched
            const auto u1 = solver.displacement();
            fe::InterfaceLoads none;
            solver.solve(step, none, 2.0); // a different trial load ...
            r = solver.solve(step);        // ... then the real one again
            ASSERT_TRUE(r.converged);
            EXPECT_NEAR(solver.displacement()[3 * probe], u1[3 * probe], 1e-15);
        }
        solver.acceptLevel();
        const double fe = solver.displacement()[3 * probe]; // x = 1: u_x = eps_xx
        const double exact = sigma0 * (1.0 / (9.0 * K) + creepCompliance(times[n]) / 3.0);
        const double error = std::abs(fe - exact) / exact;
        maxError = std::max(maxError, error);
        for (double t : {0.0, 0.1, 1.0, 10.0, 100.0})
            if (std::abs(times[n] - t) < 1e-9)
                std::printf("  %6.1f  %.9e  %.9e   %.2e\n", t, fe, exact, error);
    }
    std::printf("max relative error over %zu levels: %.2e; factorizations: %d\n", times.size(),
                maxError, solver.factorizationCount());
    EXPECT_LT(maxError, 1e-3);
    // The tangent is constant per dt (0, 0.005, 0.05, 1) and changes little between them: the
    // later dt are solved by CG on the first factorization (reuseFactorization of a linear
    // problem), never more than one factorization per distinct dt.
    EXPECT_LT(solver.factorizationCount(), 4);
    EXPECT_GE(solver.factorizationCount(), 1);
}

// Creep on long steps, where a fast term meets a slow creep: Abaqus g = (0.3, 0.3), tau = (1,
// 1000) s, G0 = 1 MPa, K = 10 MPa; dt from 0.1 s, x1.5 per level, at most 300 s, to 3 000 s (29
// levels). From t = 100 s on dt >> 1 s while the strain follows the slow term: the linear strain
// rule takes the step's mean strain rate where the fast term needs the step's final one (a
// first-order error in a decelerating creep); the quadratic rule (prony.integration: quadratic)
// takes the parabola through the last two levels. Both run the structural solver's linear path
// (the tangent from the committed history, CG on an old factorization). Reference: the creep
// compliance in closed form, J(t) = (1/G_inf) [1 + sum_k Q(p_k) / (p_k P'(p_k)) e^{p_k t}] with
// Q(s) = (s + a1)(s + a2), P(s) = Q(s) + gamma1 s (s + a2) + gamma2 s (s + a1), a_i = 1/tau_i,
// p_k the roots of P (the inverse Laplace transform of Q / (G_inf s P)).
TEST(Viscoelastic, QuadraticStrainRuleOnLongCreepSteps)
{
    const double G0 = 1e6, K = 10e6, sigma0 = 1e4, g = 0.3;
    const double Ginf = G0 * (1.0 - 2.0 * g), gamma = g / (1.0 - 2.0 * g);
    const double a1 = 1.0, a2 = 1e-3;
    // P(s) = A s^2 + B s + C
    const double A = 1.0 + 2.0 * gamma, B = a1 + a2 + gamma * (a1 + a2), C = a1 * a2;
    const double root = std::sqrt(B * B - 4.0 * A * C);
    const double p[2] = {(-B + root) / (2.0 * A), (-B - root) / (2.0 * A)};
    auto compliance = [&](double t)
    {
        double sum = 1.0;
        for (double pk : p)
            sum += (pk + a1) * (pk + a2) / (pk * (2.0 * A * pk + B)) * std::exp(pk * t);
        return sum / Ginf;
    };
    ASSERT_NEAR(compliance(0.0), 1.0 / G0, 1e-12 / G0); // the instantaneous modulus

    fsi::testing::BlockSpec spec;
    spec.cells = {1, 1, 1};
    const auto file = fsi::testing::makeBlockMesh(fsi::testing::tempFile("creep-long.msh"),
                                                  fsi::testing::TestCell::Tet10, spec);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "y0", "z0", "x1"}}, true);
    std::vector<double> times{0.0};
    for (double dt = 0.1; times.back() < 3000.0; dt = std::min(1.5 * dt, 300.0))
        times.push_back(std::min(times.back() + dt, 3000.0));
    // the largest relative error of u_x = eps_xx over the levels from t = 100 s on
    auto lateError = [&](const std::string& integration)
    {
        const auto law = viscoelasticLaw({g, g}, {1.0 / a1, 1.0 / a2}, integration);
        fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, uniaxialTraction(sigma0));
        const int probe = m.nearestNode(Eigen::Vector3d(1, 0.5, 0.5));
        double worst = 0.0;
        for (std::size_t n = 0; n < times.size(); ++n)
        {
            const auto r = solver.solve({times[n], n == 0 ? 0.0 : times[n] - times[n - 1]});
            EXPECT_TRUE(r.converged) << integration << " t = " << times[n] << ": " << r.message;
            solver.acceptLevel();
            const double exact = sigma0 * (1.0 / (9.0 * K) + compliance(times[n]) / 3.0);
            if (times[n] >= 100.0)
                worst = std::max(worst, std::abs(solver.displacement()[3 * probe] - exact) / exact);
        }
        return worst;
    };
    const double linear = lateError("linear"), quadratic = lateError("quadratic");
    std::printf("%zu levels to 3000 s: largest relative creep error from t = 100 s, linear rule "
                "%.3e, quadratic %.3e\n",
                times.size(), linear, quadratic);
    EXPECT_LT(quadratic, 0.25 * linear);
    EXPECT_LT(quadratic, 1e-4);
}
