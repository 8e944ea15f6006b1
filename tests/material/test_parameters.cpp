// SPDX-License-Identifier: GPL-3.0-or-later
// MaterialParameters: conversions (paper Table 1) and validation messages.
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"

#include <gtest/gtest.h>

#include <functional>

using namespace fsi::material;

namespace
{
MaterialParameters hapflex()
{
    MaterialParameters p;
    p.type = "viscoelastic";
    p.youngsModulus = 30.4e6;
    p.poissonRatio = 0.49;
    p.modulusBasis = "long-term";
    p.pronyConvention = "long-term-gamma";
    p.pronyCoefficients = {0.1484, 0.2115, 0.1993};
    p.pronyTimes = {4.130, 81.95, 1610.0};
    p.file = "solid.yaml";
    return p;
}

// Expects validate() to throw a message naming file and key.
void expectError(const std::function<void(MaterialParameters&)>& edit, const std::string& key)
{
    MaterialParameters p = hapflex();
    edit(p);
    try
    {
        p.validate();
        ADD_FAILURE() << "no error for key " << key;
    }
    catch (const std::runtime_error& e)
    {
        const std::string message = e.what();
        EXPECT_NE(message.find("solid.yaml: material." + key + " "), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
}
} // namespace

TEST(Parameters, HapflexTable1)
{
    const MaterialParameters p = hapflex();
    EXPECT_NO_THROW(p.validate());
    const double sum = 0.1484 + 0.2115 + 0.1993;
    const double gInf = 30.4e6 / (2.0 * 1.49), k = 30.4e6 / (3.0 * (1.0 - 0.98));
    EXPECT_NEAR(p.longTermYoungsModulus(), 30.4e6, 1e-6);
    EXPECT_NEAR(p.longTermPoissonRatio(), 0.49, 1e-14);
    EXPECT_NEAR(p.longTermShearModulus(), gInf, 1e-6);
    EXPECT_NEAR(p.bulkModulusValue(), k, 1e-5);
    EXPECT_NEAR(p.instantaneousShearModulus(), gInf * (1.0 + sum), 1e-6);
    // the paper's instantaneous E = E0 (1 + sum gamma) = 47.40 MPa (constant nu) ...
    EXPECT_NEAR(30.4e6 * (1.0 + sum), 47.40e6, 0.005e6);
    // ... while with an elastic bulk modulus the instantaneous E is 47.22 MPa (nu 0.4845)
    EXPECT_NEAR(p.instantaneousYoungsModulus(), 47.22e6, 0.005e6);
    const std::string text = p.describe();
    for (const char* item : {"0.1484", "0.2115", "0.1993", "4.13", "81.95", "1610", "3.04e+07",
                             "4.73997e+07", "long-term", "instantaneous"})
        EXPECT_NE(text.find(item), std::string::npos) << item << " missing in\n" << text;
}

TEST(Parameters, InstantaneousBasisAndAbaqusG)
{
    MaterialParameters p = hapflex();
    const double sum = 0.1484 + 0.2115 + 0.1993;
    p.pronyConvention = "abaqus-g";
    p.pronyCoefficients = {0.1484 / (1 + sum), 0.2115 / (1 + sum), 0.1993 / (1 + sum)};
    p.modulusBasis = "instantaneous";
    p.youngsModulus.reset();
    p.poissonRatio.reset();
    const MaterialParameters q = hapflex();
    p.bulkModulus = q.bulkModulusValue();
    p.shearModulus = q.instantaneousShearModulus();
    p.validate();
    EXPECT_NEAR(p.longTermShearModulus(), q.longTermShearModulus(), 1e-6);
    const auto gamma = p.longTermGamma();
    EXPECT_NEAR(gamma[0], 0.1484, 1e-14);
    EXPECT_NEAR(gamma[2], 0.1993, 1e-14);
}

TEST(Parameters, ElasticLawsAcceptEitherPair)
{
    MaterialParameters p;
    p.type = "linear-elastic";
    p.bulkModulus = 10e6;
    p.shearModulus = 1e6;
    EXPECT_NO_THROW(p.validate());
    EXPECT_NEAR(p.instantaneousShearModulus(), 1e6, 1e-9);
    EXPECT_EQ(makeMaterial(p, Kinematics::SmallStrain)->historySize(), 0u);
    EXPECT_EQ(makeMaterial(p, Kinematics::SmallStrain)->name(), "linear-elastic");
    EXPECT_NE(p.describe().find("linear-elastic"), std::string::npos);
}

TEST(Parameters, ValidationNamesTheKey)
{
    expectError([](auto& p) { p.poissonRatio = 0.5; }, "nu");
    expectError([](auto& p) { p.poissonRatio = 0.7; }, "nu");
    expectError([](auto& p) { p.poissonRatio = -1.0; }, "nu");
    expectError([](auto& p) { p.youngsModulus = -30e6; }, "E");
    expectError([](auto& p) { p.youngsModulus = 0.0; }, "E");
    expectError([](auto& p) { p.poissonRatio.reset(); }, "nu");
    expectError([](auto& p) { p.youngsModulus.reset(); }, "E");
    expectError([](auto& p) { p.bulkModulus = 1e9; }, "E");
    expectError(
        [](auto& p)
        {
            p.youngsModulus.reset();
            p.poissonRatio.reset();
            p.bulkModulus = 1e9;
            p.shearModulus = -1.0;
        },
        "G");
    expectError(
        [](auto& p)
        {
            p.youngsModulus.reset();
            p.poissonRatio.reset();
            p.shearModulus = 1e6;
        },
        "K");
    expectError([](auto& p) { p.pronyTimes[1] = 0.0; }, "prony.times");
    expectError([](auto& p) { p.pronyTimes[0] = -4.0; }, "prony.times");
    expectError([](auto& p) { p.pronyTimes.pop_back(); }, "prony.times");
    expectError([](auto& p) { p.pronyCoefficients[0] = -0.1; }, "prony.coefficients");
    expectError([](auto& p) { p.pronyCoefficients.clear(); }, "prony.coefficients");
    expectError([](auto& p) { p.pronyConvention.clear(); }, "prony.convention");
    expectError([](auto& p) { p.pronyConvention = "gamma"; }, "prony.convention");
    expectError([](auto& p) { p.modulusBasis.clear(); }, "modulus_basis");
    expectError(
        [](auto& p)
        {
            p.pronyConvention = "abaqus-g";
            p.pronyCoefficients = {0.5, 0.3, 0.2};
        },
        "prony.coefficients");
    expectError([](auto& p) { p.type.clear(); }, "type");
    expectError([](auto& p) { p.type = "hyperelastic"; }, "type");
    expectError([](auto& p) { p.type = "linear-elastic"; }, "prony");
    expectError(
        [](auto& p)
        {
            p.type = "linear-elastic";
            p.pronyConvention.clear();
            p.pronyCoefficients.clear();
            p.pronyTimes.clear();
        },
        "modulus_basis");
}

// Issue 15: gamma = 1e12 (long-term basis) gave an instantaneous nu of -1 and ran.
TEST(Parameters, AuxeticInstantaneousResponseIsRejected)
{
    expectError([](auto& p) { p.pronyCoefficients = {1e12, 0.2, 0.2}; }, "prony.coefficients");
    MaterialParameters p = hapflex();
    p.pronyCoefficients = {1e12, 0.2, 0.2};
    try
    {
        p.validate();
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("instantaneous Poisson ratio of -1"),
                  std::string::npos)
            << e.what();
    }
    // Table 1 itself stays valid: nu0 = 0.49, sum gamma = 0.559 -> instantaneous nu 0.4843.
    MaterialParameters ok = hapflex();
    EXPECT_NO_THROW(ok.validate());
    EXPECT_NEAR(ok.instantaneousPoissonRatio(), 0.4843, 5e-4);
}

TEST(Parameters, FactoryValidatesFirst)
{
    MaterialParameters p = hapflex();
    p.poissonRatio = 0.5;
    EXPECT_THROW(makeMaterial(p, Kinematics::SmallStrain), std::runtime_error);
}
