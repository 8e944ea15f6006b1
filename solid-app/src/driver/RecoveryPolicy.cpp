// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/RecoveryPolicy.hpp"

#include <sstream>

namespace fsi::driver
{

RecoveryPolicy::RecoveryPolicy(RecoveryParameters recovery,
                               acceleration::AcceleratorParameters acceleration)
    : recovery_(recovery), acceleration_(std::move(acceleration))
{
}

std::unique_ptr<acceleration::Accelerator> RecoveryPolicy::makeAccelerator() const
{
    auto accelerator = acceleration::makeAccelerator(acceleration_);
    if (relaxationScale_ != 1.0)
        accelerator->scaleRelaxation(relaxationScale_);
    return accelerator;
}

std::string RecoveryPolicy::cure(const LevelAttempt& attempt, schedule::Schedule& schedule,
                                 std::unique_ptr<acceleration::Accelerator>& accelerator)
{
    std::ostringstream s;
    if (attempt.outcome == Outcome::SolidFailed)
    {
        const double before = schedule.lastStep();
        if (schedule.cutStep(recovery_.stepFactor))
        {
            s << "redoing the level with dt = " << schedule.lastStep() << " s (was " << before
              << " s), t = " << schedule.time() << " s";
            return s.str();
        }
        if (attempt.iteration <= 1)
            return {};
    }
    relaxationScale_ *= recovery_.relaxationFactor;
    accelerator = makeAccelerator();
    s << "redoing the level from its start value with a fresh " << accelerator->name()
      << " accelerator, initial relaxation x" << relaxationScale_
      << " (kept for the rest of the run)";
    return s.str();
}

std::string RecoveryPolicy::fixFor(Outcome outcome)
{
    switch (outcome)
    {
    case Outcome::Capped:
        return ": raise coupling.max_iterations, loosen the tolerance, or set on_max_iterations: "
               "continue";
    case Outcome::Diverged:
        return ": lower the initial relaxation or use iqn-ils";
    default:
        return ": smaller time steps (coupling.time) or a softer load; check the material";
    }
}

} // namespace fsi::driver
