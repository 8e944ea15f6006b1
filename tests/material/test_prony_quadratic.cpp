// SPDX-License-Identifier: GPL-3.0-or-later
// The Prony recursion with quadratic strain interpolation (prony.integration: quadratic,
// material/Viscoelastic.hpp): exact for a strain quadratic in time at any step length, the
// linear rule where no previous step is known, a tangent that is the stress's derivative, and
// the parameter's validation. Material: K = 10 MPa, G_inf = 0.5 MPa, gamma = (0.6, 0.4),
// tau = (0.1, 10) s (reference/prony.md in the long-term convention).
#include "MaterialPoint.hpp"
#include "material/MaterialParameters.hpp"
#include "material/Prony.hpp"
#include "material/Viscoelastic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fsi::material;
using fsi::material::test::MaterialPoint;
using fsi::material::test::referenceLongTerm;
using fsi::material::test::shearStrain;

namespace
{
const double kGinf = 0.5e6;
const std::vector<double> kGamma{0.6, 0.4}, kTau{0.1, 10.0};

Viscoelastic law(Viscoelastic::Integration integration)
{
    return Viscoelastic(10e6, kGinf, kGamma, kTau, integration);
}

// Engineering shear strain gamma(t) = c1 t + c2 t^2 from rest at t = 0.
const double c1 = 2e-3, c2 = -1.5e-4;
double shear(double t)
{
    return c1 * t + c2 * t * t;
}

// Its shear stress, the hereditary integral int_0^t G(t - s) gamma'(s) ds in closed form:
// G_inf [gamma(t) + sum gamma_i (c1 tau_i (1 - e^{-t/tau_i}) + 2 c2 (tau_i t - tau_i^2 (1 -
// e^{-t/tau_i})))].
double exactStress(double t)
{
    double sum = shear(t);
    for (std::size_t i = 0; i < kGamma.size(); ++i)
    {
        const double decay = -std::expm1(-t / kTau[i]);
        sum += kGamma[i] *
               (c1 * kTau[i] * decay + 2.0 * c2 * (kTau[i] * t - kTau[i] * kTau[i] * decay));
    }
    return kGinf * sum;
}

// The largest relative stress error over the levels of `times` (from t = 0) for the history
// above: the first step (1e-6 s, linear in both rules) is too short to matter, the others have
// dt/tau from 0.05 to 200.
double worstError(Viscoelastic::Integration integration)
{
    const Viscoelastic material = law(integration);
    MaterialPoint point(material);
    point.advance(shearStrain(0.0), 0.0);
    double worst = 0.0;
    for (double t : {1e-6, 0.005, 0.05, 0.35, 1.0, 4.0, 20.0, 60.0, 2000.0})
    {
        const double stress = point.advance(shearStrain(shear(t)), t)(3);
        worst = std::max(worst, std::abs(stress - exactStress(t)) / std::abs(exactStress(t)));
    }
    return worst;
}
} // namespace

TEST(PronyQuadratic, CurvatureFactorLimits)
{
    EXPECT_EQ(pronyCurvatureFactor(0.0), 0.0);
    // series and closed form agree across the switch at 1e-3
    for (double xi : {0.999e-3, 1.001e-3})
    {
        const double phi = pronyIncrementFactor(xi);
        const double direct = 2.0 * (1.0 - phi) / xi - phi;
        const double series = xi / 6.0 - xi * xi / 12.0 + xi * xi * xi / 40.0;
        EXPECT_NEAR(pronyCurvatureFactor(xi), series, 1e-9 * series);
        EXPECT_NEAR(direct, series, 1e-8 * series);
    }
    EXPECT_NEAR(pronyCurvatureFactor(1.0), 2.0 * std::exp(-1.0) - (1.0 - std::exp(-1.0)), 1e-15);
    // 2 (1 - 1/xi) / xi - 1/xi for xi >> 1
    EXPECT_NEAR(pronyCurvatureFactor(1e6), 1e-6 - 2e-12, 1e-20);
}

TEST(PronyQuadratic, ExactForAStrainQuadraticInTime)
{
    EXPECT_LT(worstError(Viscoelastic::Integration::Quadratic), 1e-9);
    // the linear rule misses the curvature of the long steps (the test can fail)
    EXPECT_GT(worstError(Viscoelastic::Integration::Linear), 1e-3);
}

TEST(PronyQuadratic, LinearRuleWithoutAPreviousStep)
{
    // level 0 (dt = 0) leaves no rate: the first step is the linear rule's, to round-off
    const Viscoelastic linear = law(Viscoelastic::Integration::Linear);
    const Viscoelastic quadratic = law(Viscoelastic::Integration::Quadratic);
    MaterialPoint a(linear), b(quadratic);
    a.advance(shearStrain(1e-3), 0.0);
    b.advance(shearStrain(1e-3), 0.0);
    const Vector6 sa = a.advance(shearStrain(3e-3), 0.7), sb = b.advance(shearStrain(3e-3), 0.7);
    EXPECT_LT((sa - sb).norm(), 1e-14 * sa.norm());
    // the second step differs: now the rate of the first is known
    const Vector6 ta = a.advance(shearStrain(4e-3), 2.0), tb = b.advance(shearStrain(4e-3), 2.0);
    EXPECT_GT((ta - tb).norm(), 1e-4 * ta.norm());
}

TEST(PronyQuadratic, TangentIsTheDerivativeOfTheStressAndAcceptedStressMatches)
{
    const Viscoelastic material = law(Viscoelastic::Integration::Quadratic);
    MaterialPoint point(material);
    Vector6 strain;
    strain << 1e-3, -2e-4, 3e-4, 5e-4, -1e-4, 2e-4;
    point.advance(strain, 0.0);
    point.advance(1.3 * strain, 0.4);
    point.advance(1.5 * strain, 1.9);
    const TimeStep step = point.nextStep(7.0);
    Vector6 stress, probe;
    Matrix6 tangent, unused;
    const Vector6 trial = 1.6 * strain;
    material.evaluate(trial, step, point.history(), stress, tangent);
    // the law is affine in the strain: a finite difference is exact up to round-off
    for (int k = 0; k < 6; ++k)
    {
        Vector6 moved = trial;
        moved(k) += 1e-4;
        material.evaluate(moved, step, point.history(), probe, unused);
        EXPECT_LT(((probe - stress) / 1e-4 - tangent.col(k)).norm(), 1e-6 * tangent.norm())
            << "column " << k;
    }
    // the tangent's shear modulus includes the curvature term: above the linear rule's
    const Viscoelastic linear = law(Viscoelastic::Integration::Linear);
    std::vector<double> virgin(linear.historySize(), 0.0);
    Matrix6 linearTangent;
    linear.evaluate(trial, step, virgin.data(), probe, linearTangent);
    EXPECT_GT(tangent(3, 3), linearTangent(3, 3) * (1.0 + 1e-3));
    // the accepted level's stress from its own history equals its solve's stress
    std::vector<double> after(material.historySize());
    material.updateHistory(trial, step, point.history(), after.data());
    EXPECT_LT((material.acceptedStress(trial, after.data()) - stress).norm(),
              1e-12 * stress.norm());
}

TEST(PronyQuadratic, IntegrationKeyIsValidated)
{
    MaterialParameters p = referenceLongTerm();
    p.file = "solid.yaml";
    p.pronyIntegration = "quadratic";
    const auto made = makeMaterial(p, Kinematics::SmallStrain);
    const auto* viscoelastic = dynamic_cast<const Viscoelastic*>(made.get());
    ASSERT_NE(viscoelastic, nullptr);
    EXPECT_EQ(viscoelastic->integration(), Viscoelastic::Integration::Quadratic);
    EXPECT_EQ(made->historySize(), 6u * 4u + 1u);
    p.pronyIntegration = "";
    EXPECT_EQ(makeMaterial(p, Kinematics::SmallStrain)->historySize(), 6u * 3u);
    p.pronyIntegration = "cubic";
    try
    {
        p.validate();
        ADD_FAILURE() << "an unknown integration was accepted";
    }
    catch (const std::runtime_error& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("solid.yaml"), std::string::npos) << what;
        EXPECT_NE(what.find("prony.integration"), std::string::npos) << what;
        EXPECT_NE(what.find("linear or quadratic"), std::string::npos) << what;
    }
}
