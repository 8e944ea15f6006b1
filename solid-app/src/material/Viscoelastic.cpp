// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/Viscoelastic.hpp"

#include "config/YamlReader.hpp"
#include "material/MaterialParameters.hpp"
#include "material/Prony.hpp"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fsi::material
{
namespace
{
using ConstMap = Eigen::Map<const Vector6>;
using Map = Eigen::Map<Vector6>;

void checkStep(const TimeStep& step, const double* history)
{
    if (history == nullptr)
        throw std::invalid_argument("viscoelastic: committed history is null (historySize() > 0)");
    if (!(step.dt >= 0.0))
        throw std::runtime_error("viscoelastic: time step dt = " + std::to_string(step.dt) +
                                 " < 0; time levels must increase");
}

std::string number(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

void parseViscoelastic(const config::Block& b, MaterialParameters& p)
{
    readElasticModuli(b, p);
    p.modulusBasis = b.choice("modulus_basis", {"long-term", "instantaneous"});
    const config::Block prony = b.block("prony");
    prony.allowOnly({"convention", "coefficients", "times", "integration"});
    p.pronyConvention = prony.choice("convention", {"long-term-gamma", "abaqus-g"});
    p.pronyCoefficients = prony.numbers("coefficients");
    p.pronyTimes = prony.numbers("times");
    if (prony.has("integration"))
        p.pronyIntegration = prony.choice("integration", {"linear", "quadratic"});
}

void validateViscoelastic(const MaterialParameters& p)
{
    auto fail = [&p](const std::string& key, const std::string& what) { p.fail(key, what); };
    if (p.modulusBasis.empty())
        fail("modulus_basis", "is missing; say whether E/G is the long-term or the "
                              "instantaneous modulus: long-term | instantaneous");
    if (p.modulusBasis != "long-term" && p.modulusBasis != "instantaneous")
        fail("modulus_basis",
             "= '" + p.modulusBasis + "' is unknown; use long-term or instantaneous");
    if (p.pronyConvention.empty())
        fail("prony.convention", "is missing; set long-term-gamma (paper: gamma relative to the "
                                 "long-term modulus) or abaqus-g (g relative to the instantaneous "
                                 "modulus)");
    if (p.pronyConvention != "long-term-gamma" && p.pronyConvention != "abaqus-g")
        fail("prony.convention",
             "= '" + p.pronyConvention + "' is unknown; use long-term-gamma or abaqus-g");
    const auto& coefficients = p.pronyCoefficients;
    const auto& times = p.pronyTimes;
    if (!p.pronyIntegration.empty() && p.pronyIntegration != "linear" &&
        p.pronyIntegration != "quadratic")
        fail("prony.integration",
             "= '" + p.pronyIntegration + "' is unknown; use linear or quadratic");
    if (coefficients.empty())
        fail("prony.coefficients", "is empty; give at least one term or use type linear-elastic");
    if (times.size() != coefficients.size())
        fail("prony.times", "has " + std::to_string(times.size()) +
                                " entries but prony.coefficients has " +
                                std::to_string(coefficients.size()) + "; give one tau per term");
    for (std::size_t i = 0; i < times.size(); ++i)
    {
        if (!std::isfinite(times[i]) || times[i] <= 0.0)
            fail("prony.times", "[" + std::to_string(i) + "] = " + number(times[i]) +
                                    " must be a relaxation time > 0 in s");
        if (!std::isfinite(coefficients[i]) || coefficients[i] < 0.0)
            fail("prony.coefficients",
                 "[" + std::to_string(i) + "] = " + number(coefficients[i]) + " must be >= 0");
    }
    if (p.pronyConvention == "abaqus-g")
    {
        const double sum = std::accumulate(coefficients.begin(), coefficients.end(), 0.0);
        if (sum >= 1.0)
            fail("prony.coefficients", "sum of Abaqus g = " + number(sum) +
                                           " must be < 1 (long-term modulus > 0); check the "
                                           "convention (long-term-gamma?)");
    }
    // With the volumetric part elastic, a large sum of gamma makes the instantaneous response
    // auxetic (nu -> -1 as gamma grows): almost always a typo or the wrong convention.
    const double nuInstantaneous = p.instantaneousPoissonRatio();
    if (!(nuInstantaneous >= 0.0))
        fail("prony.coefficients",
             "give an instantaneous Poisson ratio of " + number(nuInstantaneous) +
                 " < 0 (instantaneous shear modulus " + number(p.instantaneousShearModulus()) +
                 " Pa against bulk modulus " + number(p.bulkModulusValue()) +
                 " Pa); check the values and prony.convention");
}
} // namespace

MaterialType Viscoelastic::entry()
{
    MaterialType t;
    t.name = "viscoelastic";
    t.keys = {"E", "nu", "K", "G", "modulus_basis", "prony"};
    t.parse = parseViscoelastic;
    t.validate = validateViscoelastic;
    t.make = [](const MaterialParameters& p) -> std::unique_ptr<Material>
    {
        return std::make_unique<Viscoelastic>(
            p.bulkModulusValue(), p.longTermShearModulus(), p.longTermGamma(), p.pronyTimes,
            p.pronyIntegration == "quadratic" ? Viscoelastic::Integration::Quadratic
                                              : Viscoelastic::Integration::Linear);
    };
    return t;
}

Viscoelastic::Viscoelastic(double bulkModulus, double longTermShearModulus,
                           std::vector<double> gamma, std::vector<double> tau,
                           Integration integration)
    : bulkModulus_(bulkModulus), longTermShearModulus_(longTermShearModulus),
      gamma_(std::move(gamma)), tau_(std::move(tau)), integration_(integration)
{
    if (gamma_.size() != tau_.size())
        throw std::invalid_argument("Viscoelastic: gamma and tau differ in length");
}

double Viscoelastic::curvatureWeight(const TimeStep& step, const double* history) const
{
    if (integration_ != Integration::Quadratic || !(step.dt > 0.0))
        return 0.0;
    const double previousDt = history[6 * (gamma_.size() + 2)];
    return previousDt > 0.0 ? step.dt / (previousDt + step.dt) : 0.0;
}

double Viscoelastic::advanceTerms(const Vector6& devSigma0, const TimeStep& step,
                                  const double* history, double* newH, Vector6* termSum) const
{
    const std::size_t n = gamma_.size();
    const Vector6 increment = devSigma0 - ConstMap(history + 6 * n);
    const double w = curvatureWeight(step, history);
    // the rate term of the quadratic rule: dt r^n (zero with the linear rule)
    const Vector6 previousChange =
        w > 0.0 ? Vector6(step.dt * ConstMap(history + 6 * (n + 1))) : Vector6::Zero();
    double shearFactor = 1.0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double xi = step.dt / tau_[i];
        const double curvature = w > 0.0 ? w * pronyCurvatureFactor(xi) : 0.0;
        const double a = gamma_[i] * (pronyIncrementFactor(xi) + curvature);
        const Vector6 term = std::exp(-xi) * ConstMap(history + 6 * i) + a * increment -
                             gamma_[i] * curvature * previousChange;
        if (newH)
            Map(newH + 6 * i) = term;
        if (termSum)
            *termSum += term;
        shearFactor += a;
    }
    return shearFactor;
}

void Viscoelastic::evaluate(const Vector6& strain, const TimeStep& step, const double* history,
                            Vector6& stress, Matrix6& tangent) const
{
    checkStep(step, history);
    const Vector6 devSigma0 = 2.0 * longTermShearModulus_ * (deviatoricProjector() * strain);
    stress = devSigma0;
    const double shearFactor = advanceTerms(devSigma0, step, history, nullptr, &stress);
    stress.head<3>().array() += bulkModulus_ * trace(strain);
    tangent = isotropicTangent(bulkModulus_, longTermShearModulus_ * shearFactor);
}

void Viscoelastic::updateHistory(const Vector6& strain, const TimeStep& step, const double* history,
                                 double* newHistory) const
{
    checkStep(step, history);
    const std::size_t n = gamma_.size();
    const Vector6 devSigma0 = 2.0 * longTermShearModulus_ * (deviatoricProjector() * strain);
    advanceTerms(devSigma0, step, history, newHistory, nullptr);
    if (integration_ == Integration::Quadratic)
    {
        const bool stepped = step.dt > 0.0;
        Map(newHistory + 6 * (n + 1)) =
            stepped ? Vector6((devSigma0 - ConstMap(history + 6 * n)) / step.dt) : Vector6::Zero();
        newHistory[6 * (n + 2)] = stepped ? step.dt : 0.0;
    }
    Map(newHistory + 6 * n) = devSigma0;
}

Vector6 Viscoelastic::acceptedStress(const Vector6& strain, const double* newHistory) const
{
    if (newHistory == nullptr)
        throw std::invalid_argument("viscoelastic: accepted history is null (historySize() > 0)");
    Vector6 stress = 2.0 * longTermShearModulus_ * (deviatoricProjector() * strain);
    for (std::size_t i = 0; i < gamma_.size(); ++i)
        stress += ConstMap(newHistory + 6 * i);
    stress.head<3>().array() += bulkModulus_ * trace(strain);
    return stress;
}

} // namespace fsi::material
