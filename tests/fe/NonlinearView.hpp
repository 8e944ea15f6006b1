// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: a material law seen as nonlinear. fe::StructuralSolver then takes its full path
// for it -- cell tangents and Newton at every solve, a fresh factorization whenever the tangent
// changes, no linear update -- the reference for the cheap path of linear problems.
#pragma once
#include "material/Material.hpp"

namespace fsi::testing
{

class NonlinearView final : public material::Material
{
public:
    explicit NonlinearView(const material::Material& law) : law_(law) {} // law outlives this
    std::string name() const override { return law_.name(); }
    std::size_t historySize() const override { return law_.historySize(); }
    void evaluate(const material::Vector6& strain, const material::TimeStep& step,
                  const double* history, material::Vector6& stress,
                  material::Matrix6& tangent) const override
    {
        law_.evaluate(strain, step, history, stress, tangent);
    }
    void updateHistory(const material::Vector6& strain, const material::TimeStep& step,
                       const double* history, double* next) const override
    {
        law_.updateHistory(strain, step, history, next);
    }
    material::Vector6 acceptedStress(const material::Vector6& strain,
                                     const double* history) const override
    {
        return law_.acceptedStress(strain, history);
    }
    void initialiseHistory(double* history) const override { law_.initialiseHistory(history); }

private:
    const material::Material& law_;
};

} // namespace fsi::testing
