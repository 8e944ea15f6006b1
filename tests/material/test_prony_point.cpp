// SPDX-License-Identifier: GPL-3.0-or-later
// Material-point checks of the viscoelastic law against ../shared/reference/prony.md:
// K = 10 MPa, G0 = 1 MPa, Abaqus g = (0.3, 0.2), tau = (0.1, 10) s.
#include "MaterialPoint.hpp"
#include "material/MaterialParameters.hpp"
#include "material/Prony.hpp"
#include "material/Viscoelastic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace fsi::material;
using fsi::material::test::MaterialPoint;
using fsi::material::test::referenceLongTerm;
using fsi::material::test::shearStrain;

namespace
{
MaterialParameters referenceAbaqus()
{
    MaterialParameters p;
    p.type = "viscoelastic";
    p.bulkModulus = 10e6;
    p.shearModulus = 1e6;
    p.modulusBasis = "instantaneous";
    p.pronyConvention = "abaqus-g";
    p.pronyCoefficients = {0.3, 0.2};
    p.pronyTimes = {0.1, 10.0};
    return p;
}

// G(t) of the reference material [Pa].
double exactG(double t)
{
    return relaxationModulus(0.5e6, {0.6, 0.4}, {0.1, 10.0}, t);
}

// Ramp (0 -> gamma0 over tr) and hold, closed form of prony.md.
double rampHoldStress(double t, double gamma0, double tr)
{
    const double m = std::min(t, tr);
    const double gi[2] = {0.3e6, 0.2e6}, tau[2] = {0.1, 10.0};
    double sum = 0.5e6 * m;
    for (int i = 0; i < 2; ++i)
        sum += gi[i] * tau[i] * (std::exp(-(t - m) / tau[i]) - std::exp(-t / tau[i]));
    return gamma0 / tr * sum;
}

double relative(double value, double reference)
{
    return std::abs(value - reference) / std::abs(reference);
}

const double tableTimes[] = {0.0, 0.1, 1.0, 10.0, 100.0};
const double relaxationTable[] = {10000.000, 8083.738, 6809.811, 5735.759, 5000.091};
const double creepTable[] = {1.000000e-2, 1.218243e-2, 1.464248e-2, 1.718286e-2, 1.999541e-2};
} // namespace

TEST(Prony, ConventionConversion)
{
    const auto gamma = gammaFromAbaqusG({0.3, 0.2});
    EXPECT_NEAR(gamma[0], 0.6, 1e-15);
    EXPECT_NEAR(gamma[1], 0.4, 1e-15);
    const auto g = abaqusGFromGamma(gamma);
    EXPECT_NEAR(g[0], 0.3, 1e-15);
    EXPECT_NEAR(g[1], 0.2, 1e-15);
    const MaterialParameters p = referenceAbaqus();
    EXPECT_NEAR(p.longTermShearModulus(), 0.5e6, 1e-9);
    EXPECT_NEAR(p.instantaneousShearModulus(), 1e6, 1e-9);
}

TEST(Prony, IncrementFactorLimits)
{
    EXPECT_EQ(pronyIncrementFactor(0.0), 1.0);
    // (1 - e^-x)/x = 1 - x/2 + x^2/6 - ...
    EXPECT_NEAR(pronyIncrementFactor(1e-10), 1.0 - 5e-11, 1e-16);
    EXPECT_NEAR(pronyIncrementFactor(1e-300), 1.0, 1e-16);
    EXPECT_NEAR(pronyIncrementFactor(1e-3), 1.0 - 5e-4 + 1e-6 / 6.0 - 1e-9 / 24.0 + 1e-12 / 120.0,
                1e-16);
    EXPECT_DOUBLE_EQ(pronyIncrementFactor(1e3), 1e-3);
    EXPECT_EQ(pronyIncrementFactor(1e308), 1.0 / 1e308);
    EXPECT_EQ(pronyIncrementFactor(INFINITY), 0.0);
}

// Step shear strain at t = 0, held: tau_xy(t) = gamma0 G(t), exact for any dt (times on grid).
class Relaxation : public ::testing::TestWithParam<double>
{
};

TEST_P(Relaxation, ReproducesTableAtAnyStep)
{
    const double dt = GetParam();
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    MaterialPoint point(*law);
    const Vector6 strain = shearStrain(0.01);
    double t = 0.0;
    double stress = point.advance(strain, 0.0)(3);
    int checked = 0;
    for (int k = 0; k < 5; ++k)
    {
        const double target = tableTimes[k];
        // march on the grid t = j dt, stopping exactly on the table time if dt skips it
        while (t < target - 1e-12 * std::max(1.0, target))
        {
            t = std::min(t + dt, target);
            stress = point.advance(strain, t)(3);
        }
        if (std::abs(t - target) > 1e-12 * std::max(1.0, target))
            continue;
        EXPECT_LT(relative(stress, 0.01 * exactG(target)), 1e-10) << "t = " << target;
        EXPECT_LT(relative(stress, relaxationTable[k]), 1e-6) << "t = " << target;
        ++checked;
    }
    EXPECT_EQ(checked, 5);
}

// dt << tau1, dt = tau1, tau1 < dt < tau2, dt >> both (the grid is clipped at table times).
INSTANTIATE_TEST_SUITE_P(Steps, Relaxation, ::testing::Values(1e-3, 0.1, 0.9, 5.0, 100.0));

TEST(Relaxation, VariableStepsAndFinalDt)
{
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    MaterialPoint point(*law);
    const Vector6 strain = shearStrain(0.01);
    point.advance(strain, 0.0);
    // directly on the table times: dt = 0.1, 0.9, 9, 90
    for (int k = 1; k < 5; ++k)
    {
        const double stress = point.advance(strain, tableTimes[k])(3);
        EXPECT_LT(relative(stress, 0.01 * exactG(tableTimes[k])), 1e-10);
    }
    // dt -> infinity: long-term modulus
    const double late = point.advance(strain, 1e12)(3);
    EXPECT_LT(relative(late, 0.01 * 0.5e6), 1e-12);
}

class RampHold : public ::testing::TestWithParam<double>
{
};

TEST_P(RampHold, MatchesClosedFormAndTable)
{
    const double dt = GetParam(); // divides t_r = 1 s
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    MaterialPoint point(*law);
    point.advance(shearStrain(0.0), 0.0);
    const int steps = static_cast<int>(std::lround(2.0 / dt));
    for (int j = 1; j <= steps; ++j)
    {
        const double t = j * dt;
        const double stress = point.advance(shearStrain(0.01 * std::min(t, 1.0)), t)(3);
        EXPECT_LT(relative(stress, rampHoldStress(t, 0.01, 1.0)), 1e-10) << "t = " << t;
        if (j == steps / 2)
        {
            EXPECT_LT(relative(stress, 7203.238), 1e-6);
        }
        if (j == steps)
        {
            EXPECT_LT(relative(stress, 6722.147), 1e-6);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Steps, RampHold, ::testing::Values(1.0, 0.5, 0.1, 1e-3));

// Step shear stress tau0 at t = 0, held: Newton on the material tangent for the strain.
TEST(Creep, ReproducesTableWithModestStep)
{
    const double tau0 = 1e4;
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    MaterialPoint point(*law);
    auto solveLevel = [&](double t) -> double
    {
        const TimeStep step = point.nextStep(t);
        Vector6 strain = shearStrain(0.0);
        Vector6 stress;
        Matrix6 tangent;
        int iterations = 0;
        for (;; ++iterations)
        {
            law->evaluate(strain, step, point.history(), stress, tangent);
            const double residual = stress(3) - tau0;
            if (std::abs(residual) <= 1e-12 * tau0 || iterations > 5)
                break;
            strain(3) -= residual / tangent(3, 3);
            if (iterations > 5)
                ADD_FAILURE() << "Newton did not converge at t = " << t;
        }
        EXPECT_LT(stress.head<3>().norm() + stress.tail<2>().norm(), 1e-9);
        point.accept(strain, step);
        return strain(3);
    };
    auto compliance = [](double t)
    { return 2e-6 - 4.2504e-7 * std::exp(-t / 0.142681) - 5.7496e-7 * std::exp(-t / 14.0173); };
    // dt = 0.01 s: 10 steps per tau1, 1e4 steps in total
    const double dt = 0.01;
    double gamma = solveLevel(0.0);
    EXPECT_LT(relative(gamma, creepTable[0]), 1e-10);
    int k = 1;
    for (int j = 1; j <= 10000; ++j)
    {
        const double t = j * dt;
        gamma = solveLevel(t);
        if (std::abs(t - tableTimes[k]) < 1e-9)
        {
            EXPECT_LT(relative(gamma, creepTable[k]), 1e-4) << "t = " << t;
            EXPECT_LT(relative(gamma, tau0 * compliance(t)), 1e-4) << "t = " << t;
            ++k;
        }
    }
    EXPECT_EQ(k, 5);
}

TEST(Conventions, LongTermGammaAndAbaqusGGiveIdenticalResponses)
{
    const auto a = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    const auto b = makeMaterial(referenceLongTerm(), Kinematics::SmallStrain);
    MaterialPoint pa(*a), pb(*b);
    double t = 0.0;
    for (int j = 0; j < 50; ++j)
    {
        Vector6 strain;
        for (int c = 0; c < 6; ++c)
            strain(c) = 1e-3 * std::sin(0.3 * j + c) * (1 + c);
        const Vector6 sa = pa.advance(strain, t), sb = pb.advance(strain, t);
        EXPECT_LT((sa - sb).norm(), 1e-12 * sa.norm()) << "level " << j;
        t += 0.05 * (1 + j % 7);
    }
}

TEST(Limits, InstantaneousAndLongTermModuli)
{
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    std::vector<double> h(law->historySize());
    law->initialiseHistory(h.data());
    Vector6 stress;
    Matrix6 tangent;
    const Vector6 strain = shearStrain(0.01);
    // dt = 0: instantaneous G0 = 1 MPa
    law->evaluate(strain, {0.0, 0.0}, h.data(), stress, tangent);
    EXPECT_NEAR(stress(3), 1e4, 1e-9);
    EXPECT_NEAR(tangent(3, 3), 1e6, 1e-6);
    EXPECT_LT((tangent - isotropicTangent(10e6, 1e6)).norm(), 1e-12 * tangent.norm());
    EXPECT_LT((law->initialTangent() - isotropicTangent(10e6, 1e6)).norm(), 1e-12 * tangent.norm());
    std::vector<double> h1(h.size());
    law->updateHistory(strain, {0.0, 0.0}, h.data(), h1.data());
    // held strain, dt -> infinity: long-term G_inf = 0.5 MPa in stress and tangent
    for (double dt : {1e9, 1e300, double(INFINITY)})
    {
        law->evaluate(strain, {dt, dt}, h1.data(), stress, tangent);
        EXPECT_NEAR(stress(3), 5e3, 1e-5) << "dt = " << dt; // 1e9 s: e-9 of the Prony term left
        EXPECT_LT((tangent - isotropicTangent(10e6, 0.5e6)).norm(), 1e-8 * tangent.norm())
            << "dt = " << dt;
        EXPECT_TRUE(stress.allFinite());
    }
    // tiny dt: no relaxation yet, no NaN
    law->evaluate(strain, {1e-300, 1e-300}, h1.data(), stress, tangent);
    EXPECT_NEAR(stress(3), 1e4, 1e-9);
    EXPECT_THROW(law->evaluate(strain, {0.0, -1.0}, h1.data(), stress, tangent),
                 std::runtime_error);
}

TEST(Limits, VolumetricResponseIsPurelyElastic)
{
    const auto law = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    MaterialPoint point(*law);
    Vector6 strain = Vector6::Zero();
    strain.head<3>().setConstant(1e-3);
    for (double t : {0.0, 0.01, 0.1, 1.0, 10.0, 100.0, 1e4})
    {
        const Vector6 stress = point.advance(strain, t);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(stress(c), 3.0 * 10e6 * 1e-3, 1e-8) << "t = " << t;
        EXPECT_NEAR(stress.tail<3>().norm(), 0.0, 1e-9);
    }
}

TEST(Limits, TotalLagrangianViscoelasticRelaxesLikeSmallStrain)
{
    const auto ss = makeMaterial(referenceAbaqus(), Kinematics::SmallStrain);
    const auto tl = makeMaterial(referenceAbaqus(), Kinematics::TotalLagrangian);
    MaterialPoint ps(*ss), pt(*tl);
    Vector6 strain;
    strain << 0.02, -0.01, 0.005, 0.03, -0.02, 0.01;
    for (double t : {0.0, 0.1, 1.0, 10.0, 100.0})
    {
        const Vector6 a = ps.advance(strain, t), b = pt.advance(strain, t);
        EXPECT_LT((a - b).norm(), 1e-12 * a.norm());
    }
}

// The stress of an accepted level from its own (updated) history equals the stress of its
// solve (committed history of the level before + the step), for finite and zero steps.
TEST(Prony, AcceptedStressEqualsTheLevelsStress)
{
    const Viscoelastic law(5e6, 1e6, {0.5, 0.3}, {0.1, 10.0});
    std::vector<double> before(law.historySize(), 0.0), after(law.historySize());
    Vector6 strain;
    strain << 1e-3, -2e-4, 3e-4, 5e-4, -1e-4, 2e-4;
    const TimeStep steps[] = {{0.0, 0.0}, {0.1, 0.1}, {2.1, 2.0}};
    for (const auto& step : steps)
    {
        Vector6 stress;
        Matrix6 D;
        law.evaluate(strain, step, before.data(), stress, D);
        law.updateHistory(strain, step, before.data(), after.data());
        const Vector6 accepted = law.acceptedStress(strain, after.data());
        EXPECT_LT((accepted - stress).norm(), 1e-12 * stress.norm()) << "t = " << step.time;
        // the old output path (the level's step applied again to the updated history) is off
        law.evaluate(strain, step, after.data(), stress, D);
        if (step.dt > 0.0)
            EXPECT_GT((accepted - stress).norm(), 1e-3 * stress.norm());
        before = after;
        strain *= 1.5;
    }
}
