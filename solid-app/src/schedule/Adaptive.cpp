// SPDX-License-Identifier: GPL-3.0-or-later
#include "schedule/Adaptive.hpp"

#include "config/YamlReader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fsi::schedule
{

namespace
{
constexpr double timeEps = 1e-12;
}

const std::vector<std::string>& AdaptiveParameters::keys()
{
    static const std::vector<std::string> k{"end",          "first_step",    "min_step",
                                            "max_step",     "target_change", "error_tolerance",
                                            "growth_limit", "shrink_limit",  "hit"};
    return k;
}

AdaptiveParameters AdaptiveParameters::parse(const config::Block& b)
{
    AdaptiveParameters p;
    p.origin = KeyOrigin::of(b);
    p.end = b.number("end");
    p.firstStep = b.number("first_step", p.firstStep);
    p.minStep = b.number("min_step", p.minStep);
    p.maxStep = b.number("max_step", p.maxStep);
    p.targetChange = b.number("target_change", p.targetChange);
    p.errorTolerance = b.number("error_tolerance", p.errorTolerance);
    p.growthLimit = b.number("growth_limit", p.growthLimit);
    p.shrinkLimit = b.number("shrink_limit", p.shrinkLimit);
    if (b.has("hit"))
        p.hit = b.numbers("hit");
    return p;
}

void AdaptiveParameters::validate() const
{
    if (!(end > 0.0) || !std::isfinite(end))
        origin.fail("end", "must be > 0 [s]");
    if (!(firstStep >= 0.0))
        origin.fail("first_step", "must be >= 0 [s] (0: a tenth of the shortest Prony time)");
    if (!(maxStep >= 0.0))
        origin.fail("max_step", "must be >= 0 [s] (0: unlimited)");
    if (!(minStep >= 0.0) || (maxStep > 0.0 && minStep > maxStep))
        origin.fail("min_step", "must be >= 0 and <= max_step [s]");
    if (!(targetChange > 0.0))
        origin.fail("target_change", "must be > 0 (relative change per level, e.g. 0.02)");
    if (!(errorTolerance >= 0.0 && errorTolerance < 1.0))
        origin.fail("error_tolerance", "must be in [0, 1) (relative path error per level, e.g. "
                                       "1e-3; 0 = steer by target_change)");
    if (!(growthLimit >= 1.0))
        origin.fail("growth_limit", "must be >= 1");
    if (!(shrinkLimit > 0.0 && shrinkLimit <= 1.0))
        origin.fail("shrink_limit", "must be in (0, 1]");
    for (double h : hit)
        if (!(h > 0.0 && h <= end))
            origin.fail("hit", "times to land on must lie in (0, end] [s]");
}

std::string AdaptiveParameters::echo() const
{
    std::ostringstream s;
    s << "{end: " << end << ", first_step: " << firstStep << ", min_step: " << minStep
      << ", max_step: " << maxStep << ", target_change: " << targetChange
      << ", error_tolerance: " << errorTolerance << ", growth_limit: " << growthLimit
      << ", shrink_limit: " << shrinkLimit << ", hit: [";
    for (std::size_t i = 0; i < hit.size(); ++i)
        s << (i ? ", " : "") << hit[i];
    s << "]}";
    return s.str();
}

void AdaptiveParameters::resolveFirstStep(const std::vector<double>& relaxationTimes)
{
    if (firstStep != 0.0)
        return;
    if (relaxationTimes.empty())
        origin.fail("first_step", "missing: give it for a material without Prony times [s]");
    firstStep = *std::min_element(relaxationTimes.begin(), relaxationTimes.end()) / 10.0;
}

Adaptive::Adaptive(const AdaptiveParameters& params) : params_(params)
{
    params_.validate();
    if (!(params_.firstStep > 0.0))
        params_.origin.fail("first_step",
                            "missing: give it for a material without Prony times [s]");
    std::sort(params_.hit.begin(), params_.hit.end());
}

bool Adaptive::hasNext() const
{
    return time_ < params_.end * (1 - timeEps);
}

double Adaptive::nextStepCandidate(double change, double pathError) const
{
    if (level_ == 0)
        return params_.firstStep;
    double factor = params_.growthLimit;
    if (params_.errorTolerance > 0.0 && std::isfinite(pathError) && pathError >= 0.0)
        factor = pathError > 0.0 ? std::clamp(0.9 * std::sqrt(params_.errorTolerance / pathError),
                                              params_.shrinkLimit, params_.growthLimit)
                                 : params_.growthLimit;
    else if (std::isfinite(change) && change > 0.0)
        factor =
            std::clamp(params_.targetChange / change, params_.shrinkLimit, params_.growthLimit);
    double dt = lastStep_ * factor;
    dt = std::max(dt, params_.minStep);
    if (params_.maxStep > 0.0)
        dt = std::min(dt, params_.maxStep);
    return dt;
}

double Adaptive::advance(double relativeChangeOfLastLevel, double pathErrorOfLastLevel)
{
    if (!hasNext())
        throw std::logic_error("Schedule::advance past the last level");
    const double step = nextStepCandidate(relativeChangeOfLastLevel, pathErrorOfLastLevel);
    double next = time_ + step;
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
    moveTo(next, next - time_);
    return time_;
}

std::string Adaptive::describe() const
{
    std::ostringstream s;
    s << "time levels: adaptive, end " << params_.end << " s, first step " << params_.firstStep
      << " s, " << (params_.errorTolerance > 0 ? "path error tolerance " : "target change ")
      << (params_.errorTolerance > 0 ? params_.errorTolerance : params_.targetChange) << ", dt in ["
      << params_.minStep << ", ";
    if (params_.maxStep > 0)
        s << params_.maxStep;
    else
        s << "inf";
    s << "] s";
    return s.str();
}

} // namespace fsi::schedule
