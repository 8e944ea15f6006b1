// SPDX-License-Identifier: GPL-3.0-or-later
// geometric: t_1 = first_step, dt_{k+1} = growth * dt_k, capped at max_step, up to end; a step
// that would pass a `hit` time (or end) is shortened to land on it, then the sequence goes on.
#pragma once

#include "config/Strategy.hpp"
#include "schedule/Schedule.hpp"

#include <string>
#include <vector>

namespace fsi::schedule
{

class Geometric;

struct GeometricParameters
{
    static constexpr const char* keyword = "geometric";
    using Strategy = Geometric;
    KeyOrigin origin;
    double end = 0.0;        // [s] > 0
    double firstStep = 0.0;  // [s] > 0
    double growth = 1.5;     // >= 1
    double maxStep = 0.0;    // [s]; 0 = unlimited
    std::vector<double> hit; // times landed on exactly [s], in (0, end]
    static const std::vector<std::string>& keys();
    static GeometricParameters parse(const config::Block& timeBlock);
    void validate() const; // also: at most kMaxTimeLevels levels
    std::string echo() const;
    std::vector<double> times() const;      // the levels, 0 first (bounded by kMaxTimeLevels + 1)
    std::vector<double> validTimes() const; // validate() and times() in one pass
};

class Geometric final : public PlannedSchedule
{
public:
    explicit Geometric(const GeometricParameters& params);
    double maxStep() const override { return maxStep_; }

protected:
    std::string name() const override { return GeometricParameters::keyword; }

private:
    double maxStep_;
};

} // namespace fsi::schedule
