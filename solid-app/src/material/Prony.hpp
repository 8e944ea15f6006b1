// SPDX-License-Identifier: GPL-3.0-or-later
// Prony-series helpers (conventions in ../shared/reference/prony.md, beside the repository).
#pragma once

#include <vector>

namespace fsi::material
{

// gamma_i = g_i / (1 - sum g). Pre: g_i >= 0, sum g < 1.
std::vector<double> gammaFromAbaqusG(const std::vector<double>& g);
// g_i = gamma_i / (1 + sum gamma). Pre: gamma_i >= 0.
std::vector<double> abaqusGFromGamma(const std::vector<double>& gamma);

// (1 - e^{-xi}) / xi for xi = dt/tau >= 0, via expm1: exact limit 1 at xi = 0,
// full accuracy for tiny xi, -> 1/xi (no overflow) for huge xi.
double pronyIncrementFactor(double xi);

// 2 (1 - phi) / xi - phi with phi = pronyIncrementFactor(xi), xi >= 0: the weight of a step's
// strain curvature in the Prony recursion with quadratic strain interpolation (Viscoelastic).
// xi/6 - xi^2/12 + xi^3/40 below xi = 1e-3 (no cancellation); exact 0 at xi = 0; -> 1/xi for
// huge xi.
double pronyCurvatureFactor(double xi);

// Relaxation modulus G(t) = G_inf (1 + sum gamma_i e^{-t/tau_i}) [Pa].
double relaxationModulus(double longTermShearModulus, const std::vector<double>& gamma,
                         const std::vector<double>& tau, double t);

} // namespace fsi::material
