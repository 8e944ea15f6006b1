// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/Prony.hpp"

#include <cmath>
#include <numeric>

namespace fsi::material
{

std::vector<double> gammaFromAbaqusG(const std::vector<double>& g)
{
    const double rest = 1.0 - std::accumulate(g.begin(), g.end(), 0.0);
    std::vector<double> gamma(g.size());
    for (std::size_t i = 0; i < g.size(); ++i)
        gamma[i] = g[i] / rest;
    return gamma;
}

std::vector<double> abaqusGFromGamma(const std::vector<double>& gamma)
{
    const double total = 1.0 + std::accumulate(gamma.begin(), gamma.end(), 0.0);
    std::vector<double> g(gamma.size());
    for (std::size_t i = 0; i < gamma.size(); ++i)
        g[i] = gamma[i] / total;
    return g;
}

double pronyIncrementFactor(double xi)
{
    if (xi == 0.0)
        return 1.0;
    return -std::expm1(-xi) / xi;
}

double pronyCurvatureFactor(double xi)
{
    if (xi < 1e-3)
        return xi / 6.0 - xi * xi / 12.0 + xi * xi * xi / 40.0;
    const double phi = pronyIncrementFactor(xi);
    return 2.0 * (1.0 - phi) / xi - phi;
}

double relaxationModulus(double longTermShearModulus, const std::vector<double>& gamma,
                         const std::vector<double>& tau, double t)
{
    double sum = 1.0;
    for (std::size_t i = 0; i < gamma.size(); ++i)
        sum += gamma[i] * std::exp(-t / tau[i]);
    return longTermShearModulus * sum;
}

} // namespace fsi::material
