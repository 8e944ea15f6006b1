// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/Viscoelastic.hpp"

#include "material/Prony.hpp"

#include <cmath>
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
} // namespace

Viscoelastic::Viscoelastic(double bulkModulus, double longTermShearModulus,
                           std::vector<double> gamma, std::vector<double> tau)
    : bulkModulus_(bulkModulus), longTermShearModulus_(longTermShearModulus),
      gamma_(std::move(gamma)), tau_(std::move(tau))
{
    if (gamma_.size() != tau_.size())
        throw std::invalid_argument("Viscoelastic: gamma and tau differ in length");
}

void Viscoelastic::evaluate(const Vector6& strain, const TimeStep& step, const double* history,
                            Vector6& stress, Matrix6& tangent) const
{
    checkStep(step, history);
    const std::size_t n = gamma_.size();
    const Vector6 devSigma0 = 2.0 * longTermShearModulus_ * (deviatoricProjector() * strain);
    const Vector6 increment = devSigma0 - ConstMap(history + 6 * n);
    stress = devSigma0;
    double shearFactor = 1.0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double xi = step.dt / tau_[i];
        const double a = gamma_[i] * pronyIncrementFactor(xi);
        stress += std::exp(-xi) * ConstMap(history + 6 * i) + a * increment;
        shearFactor += a;
    }
    stress.head<3>().array() += bulkModulus_ * trace(strain);
    tangent = isotropicTangent(bulkModulus_, longTermShearModulus_ * shearFactor);
}

void Viscoelastic::updateHistory(const Vector6& strain, const TimeStep& step, const double* history,
                                 double* newHistory) const
{
    checkStep(step, history);
    const std::size_t n = gamma_.size();
    const Vector6 devSigma0 = 2.0 * longTermShearModulus_ * (deviatoricProjector() * strain);
    const Vector6 increment = devSigma0 - ConstMap(history + 6 * n);
    for (std::size_t i = 0; i < n; ++i)
    {
        const double xi = step.dt / tau_[i];
        Map(newHistory + 6 * i) = std::exp(-xi) * ConstMap(history + 6 * i) +
                                  gamma_[i] * pronyIncrementFactor(xi) * increment;
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
