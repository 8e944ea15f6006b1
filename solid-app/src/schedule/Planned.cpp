// SPDX-License-Identifier: GPL-3.0-or-later
#include "schedule/Planned.hpp"

#include "config/YamlReader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fsi::schedule
{

namespace
{
std::vector<double> uniformTimes(const UniformParameters& p)
{
    p.validate();
    std::vector<double> t{0.0};
    const long n = std::lround(std::ceil(p.end / p.dt - 1e-9));
    for (long i = 1; i <= n; ++i)
        t.push_back(std::min(p.end, static_cast<double>(i) * p.dt));
    return t;
}

std::vector<double> listTimes(const ListParameters& p)
{
    p.validate();
    return p.times;
}
} // namespace

const std::vector<std::string>& SteadyParameters::keys()
{
    static const std::vector<std::string> k;
    return k;
}

SteadyParameters SteadyParameters::parse(const config::Block& b)
{
    return {KeyOrigin::of(b)};
}

const std::vector<std::string>& UniformParameters::keys()
{
    static const std::vector<std::string> k{"dt", "end"};
    return k;
}

UniformParameters UniformParameters::parse(const config::Block& b)
{
    UniformParameters p;
    p.origin = KeyOrigin::of(b);
    p.dt = b.number("dt");
    p.end = b.number("end");
    return p;
}

void UniformParameters::validate() const
{
    if (!(dt > 0.0) || !std::isfinite(dt))
        origin.fail("dt", "must be > 0 [s]");
    if (!(end >= 0.0) || !std::isfinite(end))
        origin.fail("end", "must be >= 0 [s]");
    if (end / dt > static_cast<double>(kMaxTimeLevels))
        origin.fail(
            "end", "= " + config::formatNumber(end) + " s gives " + config::formatNumber(end / dt) +
                       " levels of dt = " + config::formatNumber(dt) + " s, more than the " +
                       std::to_string(kMaxTimeLevels) + " allowed; raise dt or lower end");
}

std::string UniformParameters::echo() const
{
    std::ostringstream s;
    s << "{dt: " << dt << ", end: " << end << "}";
    return s.str();
}

const std::vector<std::string>& ListParameters::keys()
{
    static const std::vector<std::string> k{"times"};
    return k;
}

ListParameters ListParameters::parse(const config::Block& b)
{
    ListParameters p;
    p.origin = KeyOrigin::of(b);
    p.times = b.numbers("times");
    return p;
}

void ListParameters::validate() const
{
    if (times.empty() || times.front() != 0.0)
        origin.fail("times", "must start at 0 (the instantaneous level), e.g. [0, 0.1, 1, 10]");
    for (std::size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]) || !std::isfinite(times[i]))
            origin.fail("times", "must be strictly increasing [s]");
}

std::string ListParameters::echo() const
{
    std::ostringstream s;
    s << "{times: [";
    for (std::size_t i = 0; i < times.size(); ++i)
        s << (i ? ", " : "") << times[i];
    s << "]}";
    return s.str();
}

Uniform::Uniform(const UniformParameters& params)
    : PlannedSchedule(uniformTimes(params), params.dt), dt_(params.dt)
{
}

List::List(const ListParameters& params) : PlannedSchedule(listTimes(params)) {}

} // namespace fsi::schedule
