// SPDX-License-Identifier: GPL-3.0-or-later
// Consistent tangents against central finite differences of the stress, all laws,
// both kinematics, with history built up by a few levels.
#include "MaterialPoint.hpp"
#include "material/MaterialParameters.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <string>
#include <tuple>

using namespace fsi::material;
using fsi::material::test::MaterialPoint;

namespace
{
MaterialParameters parametersFor(const std::string& type)
{
    MaterialParameters p;
    p.type = type;
    p.youngsModulus = 30.4e6;
    p.poissonRatio = 0.49;
    if (type == "viscoelastic")
    {
        p.modulusBasis = "long-term";
        p.pronyConvention = "long-term-gamma";
        p.pronyCoefficients = {0.1484, 0.2115, 0.1993};
        p.pronyTimes = {4.130, 81.95, 1610.0};
    }
    return p;
}

Vector6 strainAt(double s)
{
    Vector6 e;
    e << 0.04, -0.03, 0.02, 0.05, -0.035, 0.025;
    return s * e;
}
} // namespace

class Tangent : public ::testing::TestWithParam<std::tuple<std::string, Kinematics>>
{
};

TEST_P(Tangent, MatchesCentralDifferences)
{
    const auto [type, kinematics] = GetParam();
    const auto law = makeMaterial(parametersFor(type), kinematics);
    MaterialPoint point(*law);
    // some history: a few accepted levels with a varying strain
    point.advance(strainAt(0.2), 0.0);
    point.advance(strainAt(0.5), 2.0);
    point.advance(strainAt(0.8), 30.0);
    // a regular step (dt = 15 s, between the relaxation times) and an instantaneous level
    for (const TimeStep step : {point.nextStep(45.0), TimeStep{30.0, 0.0}})
    {
        SCOPED_TRACE("dt = " + std::to_string(step.dt));
        const Vector6 strain = strainAt(1.0);
        Vector6 stress, plus, minus;
        Matrix6 tangent, unused;
        law->evaluate(strain, step, point.history(), stress, tangent);
        Matrix6 fd;
        const double h = 1e-6;
        for (int b = 0; b < 6; ++b)
        {
            Vector6 e = strain;
            e(b) += h;
            law->evaluate(e, step, point.history(), plus, unused);
            e(b) -= 2 * h;
            law->evaluate(e, step, point.history(), minus, unused);
            fd.col(b) = (plus - minus) / (2 * h);
        }
        EXPECT_LT((fd - tangent).norm(), 1e-6 * tangent.norm()) << "tangent\n"
                                                                << tangent << "\nfd\n"
                                                                << fd;
        EXPECT_LT((tangent - tangent.transpose()).norm(), 1e-12 * tangent.norm());
        // positive definite (the neo-Hookean dS/dE is not for ln J > mu/lambda, as here)
        if (type != "neo-hookean")
        {
            EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6>(tangent).eigenvalues().minCoeff(),
                      0.0);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Laws, Tangent,
    ::testing::Values(std::make_tuple("linear-elastic", Kinematics::SmallStrain),
                      std::make_tuple("linear-elastic", Kinematics::TotalLagrangian),
                      std::make_tuple("neo-hookean", Kinematics::TotalLagrangian),
                      std::make_tuple("viscoelastic", Kinematics::SmallStrain),
                      std::make_tuple("viscoelastic", Kinematics::TotalLagrangian)),
    [](const auto& info)
    {
        std::string name = std::get<0>(info.param) +
                           (std::get<1>(info.param) == Kinematics::SmallStrain ? "_small" : "_TL");
        for (char& c : name)
            if (c == '-')
                c = '_';
        return name;
    });

TEST(NeoHookean, SmallStrainKinematicsIsRejected)
{
    try
    {
        makeMaterial(parametersFor("neo-hookean"), Kinematics::SmallStrain);
        FAIL() << "no exception";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("material.type"), std::string::npos) << e.what();
    }
}

TEST(NeoHookean, ReducesToHookeAndMatchesKnownStress)
{
    const auto law = makeMaterial(parametersFor("neo-hookean"), Kinematics::TotalLagrangian);
    const MaterialParameters p = parametersFor("neo-hookean");
    const double k = p.bulkModulusValue(), g = p.longTermShearModulus();
    EXPECT_LT((law->initialTangent() - isotropicTangent(k, g)).norm(),
              1e-9 * isotropicTangent(k, g).norm());
    // uniaxial stretch lambda in x only (E_xx = (l^2 - 1)/2): S_xx = mu (1 - 1/l^2) + lam ln l /
    // l^2
    const double stretch = 1.1, lam = k - 2.0 * g / 3.0;
    Vector6 e = Vector6::Zero();
    e(0) = 0.5 * (stretch * stretch - 1.0);
    Vector6 s;
    Matrix6 c;
    law->evaluate(e, {0.0, 0.0}, nullptr, s, c);
    const double expected =
        g * (1.0 - 1.0 / (stretch * stretch)) + lam * std::log(stretch) / (stretch * stretch);
    EXPECT_NEAR(s(0), expected, 1e-9 * expected);
    EXPECT_NEAR(s(1), lam * std::log(stretch), 1e-9 * expected);
}

TEST(NeoHookean, InvertedDeformationThrows)
{
    const auto law = makeMaterial(parametersFor("neo-hookean"), Kinematics::TotalLagrangian);
    Vector6 e = Vector6::Zero();
    e(0) = -0.5; // C_xx = 0
    Vector6 s;
    Matrix6 c;
    EXPECT_THROW(law->evaluate(e, {0.0, 0.0}, nullptr, s, c), InadmissibleDeformation);
}

TEST(LinearElastic, StVenantKirchhoffStress)
{
    const MaterialParameters p = parametersFor("linear-elastic");
    const auto law = makeMaterial(p, Kinematics::TotalLagrangian);
    EXPECT_EQ(law->historySize(), 0u);
    const double k = p.bulkModulusValue(), mu = p.longTermShearModulus();
    const double lambda = k - 2.0 * mu / 3.0;
    const Vector6 e = strainAt(1.0);
    Vector6 s;
    Matrix6 c;
    law->evaluate(e, {0.0, 0.0}, nullptr, s, c);
    const double tr = e(0) + e(1) + e(2);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(s(a), lambda * tr + 2.0 * mu * e(a), 1e-6);
    for (int a = 3; a < 6; ++a)
        EXPECT_NEAR(s(a), mu * e(a), 1e-6); // 2 mu E_xy = mu gamma_xy
}
