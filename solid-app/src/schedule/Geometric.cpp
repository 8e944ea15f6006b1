// SPDX-License-Identifier: GPL-3.0-or-later
#include "schedule/Geometric.hpp"

#include "config/YamlReader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fsi::schedule
{

namespace
{
constexpr double timeEps = 1e-12;

} // namespace

const std::vector<std::string>& GeometricParameters::keys()
{
    static const std::vector<std::string> k{"end", "first_step", "growth", "max_step", "hit"};
    return k;
}

GeometricParameters GeometricParameters::parse(const config::Block& b)
{
    GeometricParameters p;
    p.origin = KeyOrigin::of(b);
    p.end = b.number("end");
    p.firstStep = b.number("first_step");
    p.growth = b.number("growth", p.growth);
    p.maxStep = b.number("max_step", p.maxStep);
    if (b.has("hit"))
        p.hit = b.numbers("hit");
    return p;
}

std::vector<double> GeometricParameters::times() const
{
    std::vector<double> marks = hit;
    std::sort(marks.begin(), marks.end());
    std::vector<double> t{0.0};
    double dt = firstStep;
    std::size_t nextHit = 0;
    while (t.back() < end * (1 - timeEps) && t.size() <= static_cast<std::size_t>(kMaxTimeLevels))
    {
        double next = t.back() + dt;
        while (nextHit < marks.size() && marks[nextHit] <= t.back() + timeEps)
            ++nextHit;
        if (nextHit < marks.size() && next > marks[nextHit] * (1 - timeEps))
            next = marks[nextHit];
        t.push_back(std::min(next, end));
        dt *= growth;
        if (maxStep > 0.0)
            dt = std::min(dt, maxStep);
    }
    return t;
}

void GeometricParameters::validate() const
{
    validTimes();
}

std::vector<double> GeometricParameters::validTimes() const
{
    if (!(end > 0.0) || !std::isfinite(end))
        origin.fail("end", "must be > 0 [s]");
    if (!(firstStep > 0.0))
        origin.fail("first_step", "must be > 0 [s]");
    if (!(growth >= 1.0) || !std::isfinite(growth))
        origin.fail("growth", "must be >= 1");
    if (!(maxStep >= 0.0))
        origin.fail("max_step", "must be >= 0 [s] (0: unlimited)");
    for (double h : hit)
        if (!(h > 0.0 && h <= end))
            origin.fail("hit", "times to land on must lie in (0, end] [s]");
    std::vector<double> levels = times();
    if (levels.size() > static_cast<std::size_t>(kMaxTimeLevels))
        origin.fail("first_step", "= " + config::formatNumber(firstStep) + " s with growth " +
                                      config::formatNumber(growth) + " gives more than the " +
                                      std::to_string(kMaxTimeLevels) +
                                      " levels allowed up to end; raise first_step or growth");
    return levels;
}

std::string GeometricParameters::echo() const
{
    std::ostringstream s;
    s << "{end: " << end << ", first_step: " << firstStep << ", growth: " << growth
      << ", max_step: " << maxStep << ", hit: [";
    for (std::size_t i = 0; i < hit.size(); ++i)
        s << (i ? ", " : "") << hit[i];
    s << "]}";
    return s.str();
}

Geometric::Geometric(const GeometricParameters& params)
    : PlannedSchedule(params.validTimes()), maxStep_(params.maxStep)
{
}

} // namespace fsi::schedule
