// SPDX-License-Identifier: GPL-3.0-or-later
// The time schedules by keyword: {name, keys, parse} per strategy (config/Strategy.hpp); make()
// comes with the parsed ScheduleParameters. A new schedule is its two files (class +
// parameters) and one line in Registry.cpp. config/coupled.example.yaml and
// config/solid.example.yaml document the keys (tests/config/test_documented_keys.cpp).
#pragma once

#include "config/Strategy.hpp"
#include "schedule/Schedule.hpp"

#include <string>
#include <vector>

namespace fsi::schedule
{

using ScheduleParameters = config::Strategy<Schedule>;
using ScheduleType = config::StrategyType<Schedule>;

// Every registered schedule, in registration order.
const std::vector<ScheduleType>& scheduleTypes();
// The keywords, in registration order.
std::vector<std::string> scheduleNames();

// Reads a time block: `type` (fallback when absent; empty fallback = required), the chosen
// schedule's keys and `extraKeys` (the caller's own, e.g. load_factor; read by the caller).
// Any other key is an error naming the block. Validates.
ScheduleParameters parseSchedule(const config::Block& timeBlock, const std::string& fallbackType,
                                 const std::vector<std::string>& extraKeys = {});

// Makes the schedule, first resolving an adaptive first_step of 0 from the Prony times.
std::unique_ptr<Schedule> makeSchedule(ScheduleParameters params,
                                       const std::vector<double>& relaxationTimes);

} // namespace fsi::schedule
