// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/FluidAccuracy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::driver
{

void FluidAccuracyParameters::validate() const
{
    auto fail = [](const char* key, const char* fix, double got)
    {
        char text[256];
        std::snprintf(text, sizeof text, "coupling.fluid_accuracy.%s %s (got %g)", key, fix, got);
        throw std::runtime_error(text);
    };
    if (!(finalForceTolerance > 0.0 && finalForceTolerance < 1.0))
        fail("final.force_tolerance", "must be in (0, 1), e.g. 2e-4", finalForceTolerance);
    if (!(finalResidualDrop >= 0.0 && finalResidualDrop < 1.0))
        fail("final.residual_drop", "must be in [0, 1) (0 = off)", finalResidualDrop);
    if (!(forcingFactor > 0.0 && std::isfinite(forcingFactor)))
        fail("forcing_factor", "must be > 0, e.g. 0.1", forcingFactor);
    if (!(maxForceTolerance >= finalForceTolerance && maxForceTolerance < 1.0))
        fail("max_force_tolerance", "must be in [final.force_tolerance, 1), e.g. 1e-2",
             maxForceTolerance);
    if (minIterations < 1)
        fail("min_iterations", "must be >= 1", minIterations);
}

ForcingTerm::ForcingTerm(const FluidAccuracyParameters* params)
{
    if (!params)
        return;
    controlled_ = true;
    params_ = *params;
    params_.validate();
}

FluidAccuracy ForcingTerm::finalAccuracy() const
{
    FluidAccuracy a;
    if (!controlled_)
        return a; // the fluid's own controls; every solve counts as final
    a.driverControlled = true;
    a.forceTolerance = params_.finalForceTolerance;
    a.residualDrop = params_.finalResidualDrop;
    a.minIterations = params_.minIterations;
    a.isFinal = true;
    return a;
}

FluidAccuracy ForcingTerm::forIterate(double expectedResidual, double displacementScale) const
{
    FluidAccuracy a = finalAccuracy();
    if (!controlled_)
        return a;
    double eta = params_.maxForceTolerance;
    if (expectedResidual > 0.0 && std::isfinite(expectedResidual) && displacementScale > 0.0)
        eta = std::clamp(params_.forcingFactor * expectedResidual / displacementScale,
                         params_.finalForceTolerance, params_.maxForceTolerance);
    if (eta > params_.finalForceTolerance)
    {
        // a loose solve: the residual-drop target belongs to the final accuracy only
        a.forceTolerance = eta;
        a.residualDrop = 0.0;
        a.isFinal = false;
    }
    return a;
}

std::string ForcingTerm::describe() const
{
    if (!controlled_)
        return "fluid accuracy: the fluid's own controls (fsiDict coupled) for every solve";
    char text[256];
    std::snprintf(text, sizeof text,
                  "fluid accuracy: force tolerance %g x |r|/|u| in [%g, %g], final %g "
                  "(residual drop %g), at least %d SIMPLE iterations",
                  params_.forcingFactor, params_.finalForceTolerance, params_.maxForceTolerance,
                  params_.finalForceTolerance, params_.finalResidualDrop, params_.minIterations);
    return text;
}

} // namespace fsi::driver
