// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "material/Material.hpp"
#include "material/Registry.hpp"

namespace fsi::material
{

// Compressible neo-Hookean, TotalLagrangian only:
//   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,  C = I + 2E, J = sqrt(det C)
//   S = mu (I - C^-1) + lambda ln J C^-1
//   dS/dE = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) C^-1 (.) C^-1  (symmetrised product)
// lambda = K - 2G/3, mu = G. Reduces to Hooke at E -> 0. No history.
// Throws InadmissibleDeformation if det C <= 0.
// Note: dS/dE is not positive definite once ln J > mu/lambda (volumetric expansion beyond
// ~mu/lambda, i.e. 2 % at nu = 0.49): factor the tangent as general symmetric, not SPD.
class NeoHookean final : public Material
{
public:
    // The registry entry: keyword, keys, parse, validate, make (Registry.hpp).
    static MaterialType entry();
    NeoHookean(double bulkModulus, double shearModulus); // [Pa], > 0
    std::string name() const override { return "neo-hookean"; }
    std::size_t historySize() const override { return 0; }
    void evaluate(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                  Vector6& stress, Matrix6& tangent) const override;
    void updateHistory(const Vector6&, const TimeStep&, const double*, double*) const override {}

private:
    double lambda_;
    double mu_;
};

} // namespace fsi::material
