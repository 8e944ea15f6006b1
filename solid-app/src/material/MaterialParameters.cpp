// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/MaterialParameters.hpp"

#include "config/YamlReader.hpp"
#include "material/Prony.hpp"
#include "material/Registry.hpp"

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

void MaterialParameters::fail(const std::string& key, const std::string& what) const
{
    throw std::runtime_error(file + ": " + keyPrefix + "." + key + " " + what);
}

void readElasticModuli(const config::Block& b, MaterialParameters& p)
{
    auto optionalNumber = [&b](const char* key)
    { return b.has(key) ? std::optional<double>(b.number(key)) : std::nullopt; };
    p.youngsModulus = optionalNumber("E");
    p.poissonRatio = optionalNumber("nu");
    p.bulkModulus = optionalNumber("K");
    p.shearModulus = optionalNumber("G");
}

void MaterialParameters::validate() const
{
    if (type.empty())
        fail("type", "is missing; set " + materialTypeList());
    const MaterialType* law = findMaterialType(type);
    if (!law)
        fail("type", "= '" + type + "' is unknown; use " + materialTypeList());

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
    law->validate(*this);
}

void MaterialParameters::requireNoViscoelasticData() const
{
    if (!pronyConvention.empty() || !pronyCoefficients.empty() || !pronyTimes.empty() ||
        !pronyIntegration.empty())
        fail("prony", "is given for type " + type + "; remove it or set type: viscoelastic");
    if (!modulusBasis.empty())
        fail("modulus_basis",
             "is given for type " + type + "; remove it (elastic laws have one modulus)");
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
        << ", prony.integration " << (pronyIntegration.empty() ? "linear" : pronyIntegration)
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
