// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the driver does, automatically and loudly, when a level attempt fails
// (`coupling.recovery`, see RecoveryParameters):
//   diverged (residual growth, NaN) or capped (max_iterations)
//       -> redo the level from its start value with a fresh accelerator whose relaxation is
//          scaled by relaxation_factor (cumulative, kept for the rest of the run)
//   the structural Newton failed (after its own load sub-stepping) at a level > 0
//       -> redo it with dt x step_factor (the adaptive schedule grows back); at level 0, or with
//          no step left to cut, the relaxation cure applies, but not in a level's first
//          coupling iteration, whose displacement no relaxation has touched
#pragma once

#include "acceleration/Accelerator.hpp"
#include "driver/CouplingParameters.hpp"
#include "schedule/Schedule.hpp"

#include <memory>
#include <string>

namespace fsi::driver
{

// How one attempt at a level ended.
enum class Outcome
{
    Converged,
    Capped,     // max_iterations reached
    Diverged,   // residual growth or NaN
    SolidFailed // structural Newton failed (after its own load sub-stepping)
};

struct LevelAttempt
{
    Outcome outcome = Outcome::Converged;
    std::string diagnosis; // one line, the same on every rank
    int iteration = 0;     // the coupling iteration it ended in
};

class RecoveryPolicy
{
public:
    RecoveryPolicy(RecoveryParameters recovery, acceleration::AcceleratorParameters acceleration);

    // A fresh accelerator of the configured type with the cumulative relaxation scale applied.
    std::unique_ptr<acceleration::Accelerator> makeAccelerator() const;

    // Applies the cure for a failed attempt (may cut the schedule's step or replace the
    // accelerator) and returns what it did, for the log; empty: no cure applies, nothing changed.
    std::string cure(const LevelAttempt& attempt, schedule::Schedule& schedule,
                     std::unique_ptr<acceleration::Accelerator>& accelerator);

    // Retries allowed per level.
    int maxRetries() const { return recovery_.maxRetries; }
    // Product of the relaxation cures so far (checkpointed); restore() sets it after a restart.
    double relaxationScale() const { return relaxationScale_; }
    void restore(double relaxationScale) { relaxationScale_ = relaxationScale; }

    // The fix suggested when a failure stops the run.
    static std::string fixFor(Outcome outcome);

private:
    RecoveryParameters recovery_;
    acceleration::AcceleratorParameters acceleration_;
    double relaxationScale_ = 1.0;
};

} // namespace fsi::driver
