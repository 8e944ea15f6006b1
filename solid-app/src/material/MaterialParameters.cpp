// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/MaterialParameters.hpp"

#include "material/Prony.hpp"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace fsi::material
{
namespace
{
std::string number(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

double youngs(double k, double g)
{
    return 9.0 * k * g / (3.0 * k + g);
}
double poisson(double k, double g)
{
    return (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g));
}
} // namespace

void MaterialParameters::validate() const
{
    const std::string at = file + ": " + keyPrefix + ".";
    auto fail = [&](const std::string& key, const std::string& what)
    { throw std::runtime_error(at + key + " " + what); };
    if (type.empty())
        fail("type", "is missing; set linear-elastic, neo-hookean or viscoelastic");
    if (type != "linear-elastic" && type != "neo-hookean" && type != "viscoelastic")
        fail("type",
             "= '" + type + "' is unknown; use linear-elastic, neo-hookean or viscoelastic");

    const bool haveE = youngsModulus.has_value(), haveNu = poissonRatio.has_value();
    const bool haveK = bulkModulus.has_value(), haveG = shearModulus.has_value();
    if ((haveE || haveNu) && (haveK || haveG))
        fail(haveE ? "E" : "nu", "is given together with K/G; give either (E, nu) or (K, G)");
    if (!haveE && !haveNu && !haveK && !haveG)
        fail("E", "is missing; give either (E, nu) or (K, G) in Pa");
    auto positive = [&](const std::string& key, double v)
    {
        if (!std::isfinite(v) || v <= 0.0)
            fail(key, "= " + number(v) + " must be a positive modulus in Pa");
    };
    if (haveE || haveNu)
    {
        if (!haveE)
            fail("E", "is missing (nu is given); give E in Pa");
        if (!haveNu)
            fail("nu", "is missing (E is given); give nu in (-1, 0.5)");
        positive("E", *youngsModulus);
        const double nu = *poissonRatio;
        if (!std::isfinite(nu) || nu >= 0.5)
            fail("nu", "= " + number(nu) +
                           " must be < 0.5 (incompressible limit not supported); use e.g. 0.49 "
                           "or 0.499");
        if (nu <= -1.0)
            fail("nu", "= " + number(nu) + " must be > -1");
    }
    else
    {
        if (!haveK)
            fail("K", "is missing (G is given); give the bulk modulus in Pa");
        if (!haveG)
            fail("G", "is missing (K is given); give the shear modulus in Pa");
        positive("K", *bulkModulus);
        positive("G", *shearModulus);
    }

    if (type != "viscoelastic")
    {
        if (!pronyConvention.empty() || !pronyCoefficients.empty() || !pronyTimes.empty())
            fail("prony", "is given for type " + type + "; remove it or set type: viscoelastic");
        if (!modulusBasis.empty())
            fail("modulus_basis",
                 "is given for type " + type + "; remove it (elastic laws have one modulus)");
        return;
    }

    if (modulusBasis.empty())
        fail("modulus_basis", "is missing; say whether E/G is the long-term or the "
                              "instantaneous modulus: long-term | instantaneous");
    if (modulusBasis != "long-term" && modulusBasis != "instantaneous")
        fail("modulus_basis",
             "= '" + modulusBasis + "' is unknown; use long-term or instantaneous");
    if (pronyConvention.empty())
        fail("prony.convention", "is missing; set long-term-gamma (paper: gamma relative to the "
                                 "long-term modulus) or abaqus-g (g relative to the instantaneous "
                                 "modulus)");
    if (pronyConvention != "long-term-gamma" && pronyConvention != "abaqus-g")
        fail("prony.convention",
             "= '" + pronyConvention + "' is unknown; use long-term-gamma or abaqus-g");
    if (pronyCoefficients.empty())
        fail("prony.coefficients", "is empty; give at least one term or use type linear-elastic");
    if (pronyTimes.size() != pronyCoefficients.size())
        fail("prony.times", "has " + std::to_string(pronyTimes.size()) +
                                " entries but "
                                "prony.coefficients has " +
                                std::to_string(pronyCoefficients.size()) +
                                "; give one tau per term");
    for (std::size_t i = 0; i < pronyTimes.size(); ++i)
    {
        if (!std::isfinite(pronyTimes[i]) || pronyTimes[i] <= 0.0)
            fail("prony.times", "[" + std::to_string(i) + "] = " + number(pronyTimes[i]) +
                                    " must be a relaxation time > 0 in s");
        if (!std::isfinite(pronyCoefficients[i]) || pronyCoefficients[i] < 0.0)
            fail("prony.coefficients",
                 "[" + std::to_string(i) + "] = " + number(pronyCoefficients[i]) + " must be >= 0");
    }
    if (pronyConvention == "abaqus-g")
    {
        const double sum = std::accumulate(pronyCoefficients.begin(), pronyCoefficients.end(), 0.0);
        if (sum >= 1.0)
            fail("prony.coefficients", "sum of Abaqus g = " + number(sum) +
                                           " must be < 1 (long-term modulus > 0); check the "
                                           "convention (long-term-gamma?)");
    }
    // With the volumetric part elastic, a large sum of gamma makes the instantaneous response
    // auxetic (nu -> -1 as gamma grows): almost always a typo or the wrong convention.
    const double nuInstantaneous = instantaneousPoissonRatio();
    if (!(nuInstantaneous >= 0.0))
        fail("prony.coefficients",
             "give an instantaneous Poisson ratio of " + number(nuInstantaneous) +
                 " < 0 (instantaneous shear modulus " + number(instantaneousShearModulus()) +
                 " Pa against bulk modulus " + number(bulkModulusValue()) +
                 " Pa); check the values and prony.convention");
}

std::vector<double> MaterialParameters::longTermGamma() const
{
    if (type != "viscoelastic")
        return {};
    return pronyConvention == "abaqus-g" ? gammaFromAbaqusG(pronyCoefficients) : pronyCoefficients;
}

namespace
{
double gammaSum(const MaterialParameters& p)
{
    const std::vector<double> gamma = p.longTermGamma();
    return std::accumulate(gamma.begin(), gamma.end(), 0.0);
}

double inputShear(const MaterialParameters& p)
{
    return p.shearModulus ? *p.shearModulus : *p.youngsModulus / (2.0 * (1.0 + *p.poissonRatio));
}
} // namespace

double MaterialParameters::bulkModulusValue() const
{
    return bulkModulus ? *bulkModulus : *youngsModulus / (3.0 * (1.0 - 2.0 * *poissonRatio));
}

double MaterialParameters::longTermShearModulus() const
{
    if (type == "viscoelastic" && modulusBasis == "instantaneous")
        return inputShear(*this) / (1.0 + gammaSum(*this));
    return inputShear(*this);
}

double MaterialParameters::instantaneousShearModulus() const
{
    return longTermShearModulus() * (1.0 + gammaSum(*this));
}

double MaterialParameters::longTermYoungsModulus() const
{
    return youngs(bulkModulusValue(), longTermShearModulus());
}

double MaterialParameters::instantaneousYoungsModulus() const
{
    return youngs(bulkModulusValue(), instantaneousShearModulus());
}

double MaterialParameters::longTermPoissonRatio() const
{
    return poisson(bulkModulusValue(), longTermShearModulus());
}

double MaterialParameters::instantaneousPoissonRatio() const
{
    return poisson(bulkModulusValue(), instantaneousShearModulus());
}

std::string MaterialParameters::describe() const
{
    std::ostringstream out;
    const double k = bulkModulusValue();
    out << "material " << type;
    if (type != "viscoelastic")
    {
        out << ": E = " << number(longTermYoungsModulus())
            << " Pa, G = " << number(longTermShearModulus()) << " Pa, K = " << number(k)
            << " Pa, nu = " << number(longTermPoissonRatio()) << "\n";
        return out.str();
    }
    const std::vector<double> gamma = longTermGamma();
    const std::vector<double> g = abaqusGFromGamma(gamma);
    out << " (input: prony.convention " << pronyConvention << ", modulus_basis " << modulusBasis
        << "; deviatoric Prony series, volumetric elastic)\n";
    for (std::size_t i = 0; i < gamma.size(); ++i)
        out << "  term " << i + 1 << ": gamma (long-term) = " << number(gamma[i])
            << ", g (abaqus) = " << number(g[i]) << ", tau = " << number(pronyTimes[i]) << " s\n";
    const double sum = gammaSum(*this);
    out << "  sum gamma = " << number(sum) << "\n";
    out << "  long-term:     E = " << number(longTermYoungsModulus())
        << " Pa, G = " << number(longTermShearModulus()) << " Pa, K = " << number(k)
        << " Pa, nu = " << number(longTermPoissonRatio()) << "\n";
    out << "  instantaneous: E = " << number(instantaneousYoungsModulus())
        << " Pa, G = " << number(instantaneousShearModulus()) << " Pa, K = " << number(k)
        << " Pa, nu = " << number(instantaneousPoissonRatio()) << "\n";
    out << "  (K is elastic, so the instantaneous E is below E_inf (1 + sum gamma) = "
        << number(longTermYoungsModulus() * (1.0 + sum)) << " Pa, the value at constant nu)\n";
    return out.str();
}

} // namespace fsi::material
