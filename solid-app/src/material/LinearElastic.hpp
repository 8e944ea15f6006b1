// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "material/Material.hpp"
#include "material/Registry.hpp"

namespace fsi::material
{

// Hooke's law (SmallStrain); St Venant-Kirchhoff S = lambda tr(E) I + 2 mu E (TotalLagrangian).
// The same linear map in both cases; only the meaning of strain/stress differs. No history.
class LinearElastic final : public Material
{
public:
    // The registry entry: keyword, keys, parse, validate, make (Registry.hpp).
    static MaterialType entry();
    LinearElastic(double bulkModulus, double shearModulus); // [Pa], > 0
    std::string name() const override { return "linear-elastic"; }
    std::size_t historySize() const override { return 0; }
    bool isLinearInStrain() const override { return true; }
    void evaluate(const Vector6& strain, const TimeStep& step, const double* committedHistory,
                  Vector6& stress, Matrix6& tangent) const override;
    void updateHistory(const Vector6&, const TimeStep&, const double*, double*) const override {}

private:
    Matrix6 stiffness_;
};

} // namespace fsi::material
