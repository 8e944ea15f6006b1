// SPDX-License-Identifier: GPL-3.0-or-later
// The time levels of a run (standalone solid and coupled driver alike). Time enters only
// through the material history: level 0 is t = 0 with dt = 0 (the instantaneous response),
// each later level t_n an equilibrium with the history up to t_n.
//
// Strategies by keyword (`solid.time.type`, `coupling.time.type`; Registry.hpp): steady,
// uniform, list, geometric, adaptive. Each owns its parameter struct (keyword, keys, parse,
// validate, echo; config/Strategy.hpp) next to its class. The time block is flat: its keys
// sit beside `type` (the caller checks the allowed keys, it may add its own, e.g. load_factor).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

namespace fsi::schedule
{

// Longest schedule accepted (levels), against a typo such as dt: 1e-9.
constexpr long kMaxTimeLevels = 1000000;

// Where a parameter struct came from, for one-line errors "<file>: '<path>.<key>' <what>".
struct KeyOrigin
{
    std::string file = "config";
    std::string path = "time";
    static KeyOrigin of(const config::Block& block);
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
};

class Schedule
{
public:
    static constexpr const char* kConfigKey = "time";
    virtual ~Schedule() = default;

    double time() const { return time_; } // of the current level [s]
    int level() const { return level_; }
    double lastStep() const { return lastStep_; } // dt of the current level [s] (0 at level 0)

    virtual bool hasNext() const = 0;
    // Moves to the next level, given the relative change of the solution over the level just
    // accepted and the relative error of the quasi-steady path at it (NaN: unknown); only the
    // adaptive schedule uses them. Returns the new time. Pre: hasNext().
    virtual double
    advance(double relativeChangeOfLastLevel,
            double pathErrorOfLastLevel = std::numeric_limits<double>::quiet_NaN()) = 0;
    virtual double endTime() const = 0;            // last time [s]
    virtual double maxStep() const { return 0.0; } // largest step [s]; 0: unlimited / unknown
    virtual int plannedLevels() const = 0;         // levels when known in advance, else -1
    virtual std::string describe() const = 0;      // one line for the start-up log

    // Restart: continue after the accepted `level` at `time` whose step was `lastStep`.
    virtual void resume(int level, double time, double lastStep);
    // Cure for a failed level > 0: replace its step by factor * dt (planned schedules keep the
    // original time as a later level; the adaptive rule grows the step back). Returns false,
    // changing nothing, at level 0, for a factor outside (0, 1) or a step below 1e-12 s.
    virtual bool cutStep(double factor);

protected:
    void moveTo(double time, double step);
    double time_ = 0.0;
    int level_ = 0;
    double lastStep_ = 0.0;
};

// A schedule whose times are known in advance (steady, uniform, list, geometric).
class PlannedSchedule : public Schedule
{
public:
    // times: strictly increasing, first 0. nominalStep > 0: steps within 1e-9 relative of it are
    // reported as exactly nominalStep (a bitwise-constant dt lets the solid reuse its factor).
    explicit PlannedSchedule(std::vector<double> times, double nominalStep = 0.0);
    bool hasNext() const override;
    double advance(double relativeChangeOfLastLevel,
                   double pathErrorOfLastLevel = std::numeric_limits<double>::quiet_NaN()) override;
    double endTime() const override { return planned_.back(); }
    int plannedLevels() const override { return static_cast<int>(planned_.size()); }
    std::string describe() const override;
    void resume(int level, double time, double lastStep) override;
    bool cutStep(double factor) override;
    const std::vector<double>& times() const { return planned_; }

protected:
    virtual std::string name() const = 0;

private:
    std::vector<double> planned_;
    double nominalStep_;
};

} // namespace fsi::schedule
