// SPDX-License-Identifier: GPL-3.0-or-later
#include "schedule/Registry.hpp"

#include "config/YamlReader.hpp"
#include "schedule/Adaptive.hpp"
#include "schedule/Geometric.hpp"
#include "schedule/Planned.hpp"

namespace fsi::schedule
{

const std::vector<ScheduleType>& scheduleTypes()
{
    static const std::vector<ScheduleType> types{
        config::strategyType<SteadyParameters, Schedule>(),
        config::strategyType<UniformParameters, Schedule>(),
        config::strategyType<ListParameters, Schedule>(),
        config::strategyType<GeometricParameters, Schedule>(),
        config::strategyType<AdaptiveParameters, Schedule>(),
    };
    return types;
}

std::vector<std::string> scheduleNames()
{
    std::vector<std::string> names;
    for (const auto& t : scheduleTypes())
        names.push_back(t.name);
    return names;
}

ScheduleParameters parseSchedule(const config::Block& b, const std::string& fallbackType,
                                 const std::vector<std::string>& extraKeys)
{
    const std::string type = fallbackType.empty() ? b.choice("type", scheduleNames())
                                                  : b.choice("type", scheduleNames(), fallbackType);
    const ScheduleType& chosen = config::findStrategyType(scheduleTypes(), type);
    std::vector<std::string> allowed{"type"};
    allowed.insert(allowed.end(), chosen.keys.begin(), chosen.keys.end());
    allowed.insert(allowed.end(), extraKeys.begin(), extraKeys.end());
    b.allowOnly(allowed);
    ScheduleParameters p = chosen.parse(b);
    p.validate();
    return p;
}

std::unique_ptr<Schedule> makeSchedule(ScheduleParameters params,
                                       const std::vector<double>& relaxationTimes)
{
    if (auto* adaptive = params.get<AdaptiveParameters>())
        adaptive->resolveFirstStep(relaxationTimes);
    return params.make();
}

} // namespace fsi::schedule
