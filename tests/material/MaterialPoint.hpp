// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: one integration point driven through time levels (owns its history).
#pragma once

#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"

#include <vector>

namespace fsi::material::test
{

class MaterialPoint
{
public:
    explicit MaterialPoint(const Material& law)
        : law_(law), committed_(law.historySize()), next_(law.historySize())
    {
        if (!committed_.empty())
            law_.initialiseHistory(committed_.data());
    }

    // Evaluates at level time (dt from the last accepted level; the first level has dt = 0)
    // and accepts it.
    Vector6 advance(const Vector6& strain, double time)
    {
        const TimeStep step = nextStep(time);
        Vector6 stress;
        Matrix6 tangent;
        law_.evaluate(strain, step, history(), stress, tangent);
        accept(strain, step);
        return stress;
    }

    TimeStep nextStep(double time) const { return {time, started_ ? time - time_ : 0.0}; }
    const double* history() const { return committed_.empty() ? nullptr : committed_.data(); }

    void accept(const Vector6& strain, const TimeStep& step)
    {
        if (!committed_.empty())
        {
            law_.updateHistory(strain, step, committed_.data(), next_.data());
            committed_.swap(next_);
        }
        time_ = step.time;
        started_ = true;
    }

private:
    const Material& law_;
    std::vector<double> committed_;
    std::vector<double> next_;
    double time_ = 0.0;
    bool started_ = false;
};

// The reference material of reference/prony.md in the paper's long-term convention: K = 10 MPa,
// G_inf = 0.5 MPa, gamma = (0.6, 0.4), tau = (0.1, 10) s.
inline MaterialParameters referenceLongTerm()
{
    MaterialParameters p;
    p.type = "viscoelastic";
    p.bulkModulus = 10e6;
    p.shearModulus = 0.5e6;
    p.modulusBasis = "long-term";
    p.pronyConvention = "long-term-gamma";
    p.pronyCoefficients = {0.6, 0.4};
    p.pronyTimes = {0.1, 10.0};
    return p;
}

inline Vector6 shearStrain(double gammaXy)
{
    Vector6 e = Vector6::Zero();
    e(3) = gammaXy;
    return e;
}

} // namespace fsi::material::test
