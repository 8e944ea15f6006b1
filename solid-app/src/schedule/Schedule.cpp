// SPDX-License-Identifier: GPL-3.0-or-later
#include "schedule/Schedule.hpp"

#include "config/YamlReader.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace fsi::schedule
{

KeyOrigin KeyOrigin::of(const config::Block& block)
{
    return {std::filesystem::path(block.file()).filename().string(), block.path()};
}

void KeyOrigin::fail(const std::string& key, const std::string& what) const
{
    throw std::runtime_error(file + ": '" + path + "." + key + "' " + what);
}

void Schedule::moveTo(double time, double step)
{
    lastStep_ = step;
    time_ = time;
    ++level_;
}

void Schedule::resume(int level, double time, double lastStep)
{
    if (level < 0 || !(time >= 0.0) || !(lastStep >= 0.0))
        throw std::runtime_error("restart: invalid saved time level");
    level_ = level;
    time_ = time;
    lastStep_ = lastStep;
}

bool Schedule::cutStep(double factor)
{
    const double step = lastStep_ * factor;
    if (level_ == 0 || !(factor > 0.0 && factor < 1.0) || step < 1e-12)
        return false;
    time_ = time_ - lastStep_ + step;
    lastStep_ = step;
    return true;
}

PlannedSchedule::PlannedSchedule(std::vector<double> times, double nominalStep)
    : planned_(std::move(times)), nominalStep_(nominalStep)
{
    if (planned_.empty() || planned_.front() != 0.0)
        throw std::logic_error("PlannedSchedule: the times must start at 0");
}

bool PlannedSchedule::hasNext() const
{
    return level_ + 1 < static_cast<int>(planned_.size());
}

double PlannedSchedule::advance(double, double)
{
    if (!hasNext())
        throw std::logic_error("Schedule::advance past the last level");
    const double next = planned_[level_ + 1];
    double step = next - time_;
    if (nominalStep_ > 0.0 && std::abs(step - nominalStep_) <= 1e-9 * nominalStep_)
        step = nominalStep_;
    moveTo(next, step);
    return time_;
}

void PlannedSchedule::resume(int level, double time, double lastStep)
{
    Schedule::resume(level, time, lastStep);
    // The saved run may have cut steps: level+1 entries up to `time`, then the plan.
    std::vector<double> plan;
    for (int k = 0; k <= level; ++k)
        plan.push_back(level == 0 ? 0.0 : time * k / level);
    for (double t : planned_)
        if (t > time * (1 + 1e-12) + 1e-12)
            plan.push_back(t);
    planned_ = std::move(plan);
}

bool PlannedSchedule::cutStep(double factor)
{
    if (!Schedule::cutStep(factor))
        return false;
    planned_.insert(planned_.begin() + level_, time_);
    return true;
}

std::string PlannedSchedule::describe() const
{
    std::ostringstream s;
    s << "time levels: " << name() << ", " << planned_.size() << " levels from 0 to "
      << planned_.back() << " s";
    return s.str();
}

} // namespace fsi::schedule
