// SPDX-License-Identifier: GPL-3.0-or-later
// The schedules whose times are known in advance: steady, uniform, list.
//   steady   one level at t = 0 (no time block means the same)
//   uniform  0, dt, 2 dt, ... up to end (the last step may be shorter)
//   list     the given times, strictly increasing, first 0
#pragma once

#include "config/Strategy.hpp"
#include "schedule/Schedule.hpp"

#include <string>
#include <vector>

namespace fsi::schedule
{

class Steady;
class Uniform;
class List;

struct SteadyParameters
{
    static constexpr const char* keyword = "steady";
    using Strategy = Steady;
    KeyOrigin origin;
    static const std::vector<std::string>& keys();
    static SteadyParameters parse(const config::Block& timeBlock);
    void validate() const {}
    std::string echo() const { return "{}"; }
};

struct UniformParameters
{
    static constexpr const char* keyword = "uniform";
    using Strategy = Uniform;
    KeyOrigin origin;
    double dt = 0.0;  // [s] > 0
    double end = 0.0; // [s] >= 0; at most kMaxTimeLevels steps
    static const std::vector<std::string>& keys();
    static UniformParameters parse(const config::Block& timeBlock);
    void validate() const; // throws "<file>: '<path>.<key>' ..."
    std::string echo() const;
};

struct ListParameters
{
    static constexpr const char* keyword = "list";
    using Strategy = List;
    KeyOrigin origin;
    std::vector<double> times; // [s], strictly increasing, first 0
    static const std::vector<std::string>& keys();
    static ListParameters parse(const config::Block& timeBlock);
    void validate() const;
    std::string echo() const;
};

class Steady final : public PlannedSchedule
{
public:
    explicit Steady(const SteadyParameters& = {}) : PlannedSchedule({0.0}) {}

protected:
    std::string name() const override { return SteadyParameters::keyword; }
};

class Uniform final : public PlannedSchedule
{
public:
    explicit Uniform(const UniformParameters& params);
    double maxStep() const override { return dt_; }

protected:
    std::string name() const override { return UniformParameters::keyword; }

private:
    double dt_;
};

class List final : public PlannedSchedule
{
public:
    explicit List(const ListParameters& params);

protected:
    std::string name() const override { return ListParameters::keyword; }
};

} // namespace fsi::schedule
