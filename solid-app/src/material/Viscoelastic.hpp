// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "material/Material.hpp"
#include "material/Registry.hpp"

#include <vector>

namespace fsi::material
{

// Generalized Maxwell model on the deviatoric part, elastic volumetric part (paper eqs. 5-9):
//   sigma^{n+1} = K tr(eps) I + dev sigma0^{n+1} + sum_i h_i^{n+1}
//   dev sigma0  = 2 G_inf dev(eps)              (base law: long-term modulus, gamma long-term)
//   h_i^{n+1}   = e^{-xi_i} h_i^n + gamma_i (1 - e^{-xi_i})/xi_i [dev sigma0^{n+1} - dev sigma0^n]
//   xi_i = dt/tau_i; the factor is 1 at dt = 0 (instantaneous) and -> 0 for dt >> tau_i.
//   Tangent (eq. 9): K II + 2 G_inf [1 + sum gamma_i (1 - e^{-xi_i})/xi_i] (I - II/3).
// Exact for strain linear in time over the step (any dt/tau): Integration::Linear.
//
// Integration::Quadratic (prony.integration: quadratic) interpolates dev sigma0 over the step by
// the parabola through the last two accepted levels and the new one (the previous step's rate
// r^n and length dt^n are kept in the history). With D = dev sigma0^{n+1} - dev sigma0^n,
// w = dt/(dt^n + dt) and psi_i = pronyCurvatureFactor(xi_i):
//   h_i^{n+1} = e^{-xi_i} h_i^n + gamma_i [(phi_i + w psi_i) D - w psi_i dt r^n],
//   tangent shear modulus G_inf [1 + sum gamma_i (phi_i + w psi_i)].
// Exact for dev sigma0 quadratic in time; for a term with dt >> tau_i it takes the strain rate
// at the step's end instead of the step's mean (the linear rule's first-order error in a
// decelerating creep, cases/hydrofoil/README.md). The first step after an instantaneous level
// (dt = 0) or a virgin history is linear.
//
// TotalLagrangian: the same recursion on the 2nd Piola-Kirchhoff stress of the
// St Venant-Kirchhoff base law, S0 = K tr(E) I + 2 G_inf dev(E) (Kaliske & Rothert style).
// "Deviatoric" is the plain deviator in the REFERENCE configuration, dev A = A - tr(A)/3 I
// (trace w.r.t. the reference metric I, not the isochoric DEV A = A - (A:C)/3 C^-1).
// The law is then linear in E: an SVK solid whose shear modulus relaxes; its tangent is
// constant per dt and it reduces exactly to the small-strain law as E -> eps.
//
// History per integration point, Voigt, tensor-shear components [Pa]:
//   Linear:    6 (N + 1) doubles [h_1 (6) | ... | h_N (6) | dev sigma0^n (6)];
//   Quadratic: 6 (N + 2) + 1     [... as Linear ... | r^n (6) [Pa/s] | dt^n (1) [s]], dt^n = 0:
//              no previous step (the next step is linear).
class Viscoelastic final : public Material
{
public:
    // The registry entry: keyword, keys, parse, validate, make (Registry.hpp).
    static MaterialType entry();
    enum class Integration
    {
        Linear,
        Quadratic
    };
    // bulkModulus K, longTermShearModulus G_inf [Pa] > 0; gamma_i >= 0 relative to G_inf;
    // tau_i > 0 [s]; equal lengths.
    Viscoelastic(double bulkModulus, double longTermShearModulus, std::vector<double> gamma,
                 std::vector<double> tau, Integration integration = Integration::Linear);
    std::string name() const override { return "viscoelastic"; }
    std::size_t historySize() const override
    {
        return integration_ == Integration::Quadratic ? 6 * (gamma_.size() + 2) + 1
                                                      : 6 * (gamma_.size() + 1);
    }
    bool isLinearInStrain() const override { return true; }
    void evaluate(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                  Vector6& stress, Matrix6& tangent) const override;
    void updateHistory(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                       double* newHistory) const override;
    // K tr(eps) I + dev sigma0(eps) + sum_i h_i^{n+1}: the h_i of newHistory already hold the
    // level's increment.
    Vector6 acceptedStress(const Vector6& strain, const double* newHistory) const override;

    std::size_t termCount() const { return gamma_.size(); }
    Integration integration() const { return integration_; }

private:
    // Weight w = dt/(dt^n + dt) of the quadratic rule for this step and committed history
    // (0: the linear rule).
    double curvatureWeight(const TimeStep& step, const double* history) const;
    // The h_i^{n+1} of the recursion for dev sigma0^{n+1}, written to newH (6 N doubles) and/or
    // added to termSum (either may be null); returns the tangent's shear factor
    // 1 + sum gamma_i (phi_i + w psi_i).
    double advanceTerms(const Vector6& devSigma0, const TimeStep& step, const double* history,
                        double* newH, Vector6* termSum) const;

    double bulkModulus_;
    double longTermShearModulus_;
    std::vector<double> gamma_;
    std::vector<double> tau_;
    Integration integration_;
};

} // namespace fsi::material
