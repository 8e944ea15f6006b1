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
// Exact for strain linear in time over the step (any dt/tau).
//
// TotalLagrangian: the same recursion on the 2nd Piola-Kirchhoff stress of the
// St Venant-Kirchhoff base law, S0 = K tr(E) I + 2 G_inf dev(E) (Kaliske & Rothert style).
// "Deviatoric" is the plain deviator in the REFERENCE configuration, dev A = A - tr(A)/3 I
// (trace w.r.t. the reference metric I, not the isochoric DEV A = A - (A:C)/3 C^-1).
// The law is then linear in E: an SVK solid whose shear modulus relaxes; its tangent is
// constant per dt and it reduces exactly to the small-strain law as E -> eps.
//
// History per integration point, historySize() = 6 (N + 1) doubles:
//   [h_1 (6) | ... | h_N (6) | dev sigma0^n (6)], Voigt, tensor-shear components [Pa].
class Viscoelastic final : public Material
{
public:
    // The registry entry: keyword, keys, parse, validate, make (Registry.hpp).
    static MaterialType entry();
    // bulkModulus K, longTermShearModulus G_inf [Pa] > 0; gamma_i >= 0 relative to G_inf;
    // tau_i > 0 [s]; equal lengths.
    Viscoelastic(double bulkModulus, double longTermShearModulus, std::vector<double> gamma,
                 std::vector<double> tau);
    std::string name() const override { return "viscoelastic"; }
    std::size_t historySize() const override { return 6 * (gamma_.size() + 1); }
    bool isLinearInStrain() const override { return true; }
    void evaluate(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                  Vector6& stress, Matrix6& tangent) const override;
    void updateHistory(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                       double* newHistory) const override;
    // K tr(eps) I + dev sigma0(eps) + sum_i h_i^{n+1}: the h_i of newHistory already hold the
    // level's increment.
    Vector6 acceptedStress(const Vector6& strain, const double* newHistory) const override;

    std::size_t termCount() const { return gamma_.size(); }

private:
    double bulkModulus_;
    double longTermShearModulus_;
    std::vector<double> gamma_;
    std::vector<double> tau_;
};

} // namespace fsi::material
