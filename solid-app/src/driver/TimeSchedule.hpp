// SPDX-License-Identifier: GPL-3.0-or-later
//
// Quasi-steady time levels of a coupled run. Time enters only through the material history:
// each level t_n is an equilibrium of steady flow and the solid with the history up to t_n.
// Level 0 is t = 0 with dt = 0: the instantaneous (elastic, instantaneous-modulus) response.
//
// Kinds (keyword `coupling.time.type`):
//   steady     one level at t = 0 (no time block at all means the same)
//   list       the given times (strictly increasing, first 0)
//   geometric  t_1 = first_step, dt_{k+1} = growth * dt_k, capped at max_step, up to end
//   adaptive   dt_{k+1} = dt_k * clamp(target_change / change_k, shrink_limit, growth_limit),
//              change_k = |u_k - u_{k-1}| / |u_k| of the interface displacement over level k,
//              or, with error_tolerance > 0, steered by the error of the quasi-steady path:
//              dt_{k+1} = dt_k * clamp(0.9 sqrt(error_tolerance / e_k), shrink, growth) with
//              e_k = |u_k - u_lin| / |u_k|, u_lin the linear extrapolation of the two levels
//              before k to t_k (the local error of a history that is piecewise linear in time,
//              as the Prony recursion assumes, is of the same order dt^2 u''); levels whose
//              e_k is unknown (the first two) use the change rule.
//              dt within [min_step, max_step]; `hit` times (e.g. 50, 360 s) are landed on
//              exactly (two equal steps when one would leave a sliver before the hit time).
//              first_step defaults to min(tau_i)/10 from the Prony series.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace fsi::driver
{

struct TimeScheduleParameters
{
    std::string type = "steady"; // steady | list | geometric | adaptive
    std::vector<double> times;   // list [s]
    double end = 0.0;            // geometric, adaptive [s]
    double firstStep = 0.0;      // geometric, adaptive [s]; adaptive: 0 = from the Prony times
    double growth = 1.5;         // geometric factor (> 1)
    double maxStep = 0.0;        // geometric, adaptive [s]; 0 = unlimited
    double minStep = 0.0;        // adaptive [s]
    double targetChange = 0.02;  // adaptive: wanted relative interface change per level
    double growthLimit = 2.0;    // adaptive: largest dt_{k+1}/dt_k
    double shrinkLimit = 0.5;    // adaptive: smallest dt_{k+1}/dt_k
    double errorTolerance = 0.0; // adaptive: relative path error per level (0 = change rule)
    std::vector<double> hit;     // adaptive/geometric: times to land on exactly [s]
    // Throws std::runtime_error naming coupling.time.<key> and the fix.
    void validate() const;
};

class TimeSchedule
{
public:
    // relaxationTimes: the Prony tau_i [s] (may be empty: elastic), for the adaptive default.
    TimeSchedule(TimeScheduleParameters params, std::vector<double> relaxationTimes);

    // Time of level 0 (always 0) and whether another level follows.
    double time() const { return time_; }
    int level() const { return level_; }
    bool hasNext() const;
    // dt of the next level, given the relative interface change and the relative path error
    // (NaN: unknown) of the level just accepted (both ignored unless adaptive). Returns the new
    // time; level() increases by one.
    double advance(double relativeChangeOfLastLevel,
                   double pathErrorOfLastLevel = std::numeric_limits<double>::quiet_NaN());
    // Last time of the schedule [s] (0 for steady) and the largest step (0: unlimited) [s].
    double endTime() const;
    double maxStep() const { return params_.maxStep; }
    double lastStep() const { return lastStep_; }
    // Number of levels when known in advance (steady, list, geometric); -1 for adaptive.
    int plannedLevels() const;
    std::string describe() const;

    // Restart: continue after the accepted `level` at `time` whose step was `lastStep`. Planned
    // schedules keep their times after `time`.
    void resume(int level, double time, double lastStep);
    // Cure for a failed level > 0: replace the current step by factor * dt, keeping the level's
    // original time as a later level (planned schedules) or letting the adaptive rule grow back.
    // Returns false (nothing changed) at level 0 or when the step would fall below 1e-12 s.
    bool cutStep(double factor);

private:
    double nextStepCandidate(double change, double pathError) const;
    TimeScheduleParameters params_;
    double time_ = 0.0;
    int level_ = 0;
    double lastStep_ = 0.0;
    std::vector<double> planned_; // steady/list/geometric: all times
};

} // namespace fsi::driver
