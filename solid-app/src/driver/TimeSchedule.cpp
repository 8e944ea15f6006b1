// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/TimeSchedule.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
[[noreturn]] void fail(const std::string& key, const std::string& what)
{
    throw std::runtime_error("coupling.time." + key + ": " + what);
}
constexpr double timeEps = 1e-12;
std::string formatG(double x)
{
    std::ostringstream s;
    s << x;
    return s.str();
}
} // namespace

void TimeScheduleParameters::validate() const
{
    if (type == "steady")
        return;
    if (type == "list")
    {
        if (times.empty() || times.front() != 0.0)
            fail("times", "must start at 0 (the instantaneous level), e.g. [0, 10, 60]");
        for (std::size_t i = 1; i < times.size(); ++i)
            if (!(times[i] > times[i - 1]))
                fail("times", "must be strictly increasing");
        return;
    }
    if (type != "geometric" && type != "adaptive")
        fail("type", "unknown '" + type + "' (steady | list | geometric | adaptive)");
    if (!(end > 0.0))
        fail("end", "must be > 0 s");
    if (type == "geometric" && !(firstStep > 0.0))
        fail("first_step", "must be > 0 s");
    if (firstStep < 0.0)
        fail("first_step", "must be >= 0 s (0: a tenth of the shortest relaxation time)");
    if (maxStep < 0.0)
        fail("max_step", "must be >= 0 s (0: unlimited)");
    if (type == "geometric" && !(growth >= 1.0))
        fail("growth", "must be >= 1");
    if (type == "adaptive")
    {
        if (minStep < 0.0 || (maxStep > 0.0 && minStep > maxStep))
            fail("min_step", "must be >= 0 and <= max_step");
        if (!(targetChange > 0.0))
            fail("target_change", "must be > 0 (relative interface change per level, e.g. 0.02)");
        if (!(growthLimit >= 1.0))
            fail("growth_limit", "must be >= 1");
        if (!(shrinkLimit > 0.0 && shrinkLimit <= 1.0))
            fail("shrink_limit", "must be in (0, 1]");
        if (!(errorTolerance >= 0.0 && errorTolerance < 1.0))
            fail("error_tolerance", "must be in [0, 1) (relative path error per level, e.g. 1e-3; "
                                    "0 = steer by target_change)");
    }
    for (double h : hit)
        if (!(h > 0.0 && h <= end))
            fail("hit", "times to land on must lie in (0, end]");
}

TimeSchedule::TimeSchedule(TimeScheduleParameters params, std::vector<double> relaxationTimes)
    : params_(std::move(params))
{
    params_.validate();
    std::sort(params_.hit.begin(), params_.hit.end());
    if (params_.type == "adaptive" && params_.firstStep == 0.0)
    {
        if (relaxationTimes.empty())
            fail("first_step", "required for an elastic material (no Prony times to derive it)");
        params_.firstStep = *std::min_element(relaxationTimes.begin(), relaxationTimes.end()) / 10;
    }
    if (params_.type == "steady")
        planned_ = {0.0};
    else if (params_.type == "list")
        planned_ = params_.times;
    else if (params_.type == "geometric")
    {
        planned_ = {0.0};
        double dt = params_.firstStep;
        std::size_t nextHit = 0;
        while (planned_.back() < params_.end * (1 - timeEps))
        {
            double t = planned_.back() + dt;
            while (nextHit < params_.hit.size() && params_.hit[nextHit] <= planned_.back() + timeEps)
                ++nextHit;
            if (nextHit < params_.hit.size() && t > params_.hit[nextHit] * (1 - timeEps))
                t = params_.hit[nextHit];
            planned_.push_back(std::min(t, params_.end));
            dt *= params_.growth;
            if (params_.maxStep > 0.0)
                dt = std::min(dt, params_.maxStep);
        }
    }
}

bool TimeSchedule::hasNext() const
{
    if (params_.type == "adaptive")
        return time_ < params_.end * (1 - timeEps);
    return level_ + 1 < static_cast<int>(planned_.size());
}

int TimeSchedule::plannedLevels() const
{
    return params_.type == "adaptive" ? -1 : static_cast<int>(planned_.size());
}

double TimeSchedule::endTime() const
{
    return params_.type == "adaptive" ? params_.end : planned_.back();
}

double TimeSchedule::nextStepCandidate(double change, double pathError) const
{
    if (level_ == 0)
        return params_.firstStep;
    double factor = params_.growthLimit;
    if (params_.errorTolerance > 0.0 && std::isfinite(pathError) && pathError >= 0.0)
        factor = pathError > 0.0 ? std::clamp(0.9 * std::sqrt(params_.errorTolerance / pathError),
                                              params_.shrinkLimit, params_.growthLimit)
                                 : params_.growthLimit;
    else if (std::isfinite(change) && change > 0.0)
        factor = std::clamp(params_.targetChange / change, params_.shrinkLimit, params_.growthLimit);
    double dt = lastStep_ * factor;
    dt = std::max(dt, params_.minStep);
    if (params_.maxStep > 0.0)
        dt = std::min(dt, params_.maxStep);
    return dt;
}

double TimeSchedule::advance(double relativeChangeOfLastLevel, double pathErrorOfLastLevel)
{
    if (!hasNext())
        throw std::logic_error("TimeSchedule::advance past the last level");
    double next;
    if (params_.type == "adaptive")
    {
        const double step = nextStepCandidate(relativeChangeOfLastLevel, pathErrorOfLastLevel);
        next = time_ + step;
        for (double h : params_.hit)
            if (h > time_ * (1 + timeEps) + timeEps)
            {
                // land on h; when one step would stop short of h by less than a step, take two
                // equal steps to h instead of a full step and a sliver
                if (next > h * (1 - timeEps))
                    next = h;
                else if (h - time_ < 2 * step)
                    next = time_ + 0.5 * (h - time_);
                break;
            }
        // Do not leave a sliver before the end.
        if (next > params_.end * (1 - timeEps) || params_.end - next < 0.1 * (next - time_))
            next = params_.end;
    }
    else
        next = planned_[level_ + 1];
    lastStep_ = next - time_;
    time_ = next;
    ++level_;
    return time_;
}

void TimeSchedule::resume(int level, double time, double lastStep)
{
    if (level < 0 || !(time >= 0.0) || !(lastStep >= 0.0))
        throw std::runtime_error("restart: invalid saved time level");
    if (params_.type != "adaptive")
    {
        // The saved run may have cut steps: keep level+1 entries up to `time`, then the plan.
        std::vector<double> plan;
        for (int k = 0; k <= level; ++k)
            plan.push_back(level == 0 ? 0.0 : time * k / level);
        for (double t : planned_)
            if (t > time * (1 + timeEps) + timeEps)
                plan.push_back(t);
        planned_ = std::move(plan);
    }
    level_ = level;
    time_ = time;
    lastStep_ = lastStep;
}

bool TimeSchedule::cutStep(double factor)
{
    const double step = lastStep_ * factor;
    if (level_ == 0 || !(factor > 0.0 && factor < 1.0) || step < 1e-12)
        return false;
    const double previous = time_ - lastStep_;
    if (params_.type != "adaptive")
        planned_.insert(planned_.begin() + level_, previous + step);
    time_ = previous + step;
    lastStep_ = step;
    return true;
}

std::string TimeSchedule::describe() const
{
    std::ostringstream s;
    s << "time levels: " << params_.type;
    if (params_.type == "adaptive")
        s << ", end " << params_.end << " s, first step " << params_.firstStep << " s, "
          << (params_.errorTolerance > 0 ? "path error tolerance " : "target change ")
          << (params_.errorTolerance > 0 ? params_.errorTolerance : params_.targetChange)
          << ", dt in [" << params_.minStep << ", "
          << (params_.maxStep > 0 ? formatG(params_.maxStep) : std::string("inf")) << "] s";
    else
        s << ", " << planned_.size() << " levels from 0 to " << planned_.back() << " s";
    return s.str();
}

} // namespace fsi::driver
