// SPDX-License-Identifier: GPL-3.0-or-later
// The time schedules (schedule/): level times, steps, landing on hit times, restart and cure.
#include "schedule/Adaptive.hpp"
#include "schedule/Geometric.hpp"
#include "schedule/Planned.hpp"
#include "schedule/Registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

using namespace fsi::schedule;

namespace
{
std::vector<double> allTimes(Schedule& s, double change = 0.01)
{
    std::vector<double> t{s.time()};
    while (s.hasNext())
        t.push_back(s.advance(change));
    return t;
}
template <class P> std::vector<double> timesOf(const P& params, double change = 0.01)
{
    auto s = makeSchedule(params, {});
    return allTimes(*s, change);
}
} // namespace

TEST(Schedule, SteadyIsOneInstantaneousLevel)
{
    Steady s;
    EXPECT_EQ(allTimes(s), std::vector<double>{0.0});
    EXPECT_EQ(s.plannedLevels(), 1);
}

TEST(Schedule, GeometricLandsOnHitTimesAndEnd)
{
    GeometricParameters p;
    p.end = 3600;
    p.firstStep = 1;
    p.growth = 2;
    p.maxStep = 600;
    p.hit = {50, 360};
    const auto t = timesOf(p);
    EXPECT_EQ(t.front(), 0.0);
    EXPECT_DOUBLE_EQ(t.back(), 3600.0);
    EXPECT_NE(std::find(t.begin(), t.end(), 50.0), t.end());
    EXPECT_NE(std::find(t.begin(), t.end(), 360.0), t.end());
    for (std::size_t i = 1; i < t.size(); ++i)
    {
        EXPECT_GT(t[i], t[i - 1]);
        EXPECT_LE(t[i] - t[i - 1], 600.0 + 1e-9);
    }
    // 0,1,3,7,15,31,50(hit),63? no: after the hit the geometric step continues from its sequence.
    EXPECT_DOUBLE_EQ(t[1], 1.0);
    EXPECT_DOUBLE_EQ(t[2], 3.0);
}

TEST(Schedule, AdaptiveStartsFromTheShortestRelaxationTimeAndFollowsTheChange)
{
    AdaptiveParameters p;
    p.end = 100;
    p.targetChange = 0.02;
    p.growthLimit = 2;
    p.shrinkLimit = 0.5;
    p.hit = {50};
    auto made = makeSchedule(p, {4.13, 81.95, 1610});
    Schedule& s = *made;
    EXPECT_DOUBLE_EQ(s.advance(0.0), 0.413);              // first step = min tau / 10
    EXPECT_DOUBLE_EQ(s.advance(0.04), 0.413 + 0.2065);    // change 2x target: halve
    EXPECT_NEAR(s.advance(0.001), 0.6195 + 0.413, 1e-12); // small change: growth limit 2
    std::vector<double> t;
    while (s.hasNext())
        t.push_back(s.advance(0.001));
    EXPECT_NE(std::find(t.begin(), t.end(), 50.0), t.end());
    EXPECT_DOUBLE_EQ(t.back(), 100.0);
    EXPECT_FALSE(s.hasNext());
}

TEST(Schedule, InvalidParametersNameTheKey)
{
    ListParameters p;
    p.origin.path = "coupling.time";
    p.times = {1, 2};
    try
    {
        p.validate();
        FAIL();
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("coupling.time.times"), std::string::npos);
    }
    AdaptiveParameters a;
    a.end = 10;
    EXPECT_THROW(makeSchedule(a, {}), std::runtime_error); // elastic: first_step required
    EXPECT_THROW(Adaptive{a}, std::runtime_error);
}

// Restart: resuming after level 2 of a list gives the remaining planned times.
TEST(Schedule, ResumeContinuesWithThePlannedTimes)
{
    ListParameters p;
    p.times = {0, 1, 2, 5, 10};
    auto made = makeSchedule(p, {});
    Schedule& s = *made;
    s.resume(2, 2.0, 1.0);
    EXPECT_EQ(s.level(), 2);
    EXPECT_EQ(allTimes(s), (std::vector<double>{2, 5, 10}));
}

// The time-step cure inserts a shorter level and keeps the planned time as the next one.
TEST(Schedule, CutStepInsertsAShorterLevel)
{
    ListParameters p;
    p.times = {0, 4, 8};
    auto made = makeSchedule(p, {});
    Schedule& s = *made;
    EXPECT_FALSE(s.cutStep(0.5)); // level 0 has no step
    s.advance(0.0);
    ASSERT_TRUE(s.cutStep(0.25));
    EXPECT_DOUBLE_EQ(s.time(), 1.0);
    EXPECT_DOUBLE_EQ(s.lastStep(), 1.0);
    EXPECT_EQ(s.level(), 1);
    EXPECT_EQ(allTimes(s), (std::vector<double>{1, 4, 8}));
}

// error_tolerance: the step follows the path error e with dt_new = dt * 0.9 sqrt(tol / e),
// clamped to [shrink_limit, growth_limit]; an unknown e (NaN) falls back to the change rule.
TEST(Schedule, AdaptiveStepFollowsThePathError)
{
    AdaptiveParameters p;
    p.end = 1000;
    p.firstStep = 1;
    p.targetChange = 0.1;
    p.errorTolerance = 1e-3;
    p.growthLimit = 3;
    p.shrinkLimit = 0.25;
    auto made = makeSchedule(p, {});
    Schedule& s = *made;
    EXPECT_DOUBLE_EQ(s.advance(0.5), 1.0); // level 1: first_step
    // unknown path error: change rule, 0.1 / 0.05 = 2
    EXPECT_DOUBLE_EQ(s.advance(0.05, std::numeric_limits<double>::quiet_NaN()) - 1.0, 2.0);
    // e = tol / 4: factor 0.9 * 2 = 1.8 (the change is ignored)
    EXPECT_NEAR(s.advance(10.0, 2.5e-4) - 3.0, 2.0 * 1.8, 1e-12);
    // e = 100 tol: factor 0.09, clamped to the shrink limit
    const double before = s.lastStep();
    const double t = s.time();
    EXPECT_NEAR(s.advance(1e-6, 0.1) - t, 0.25 * before, 1e-12);
    // e = 0 (exactly linear history): the growth limit
    const double t2 = s.time();
    EXPECT_NEAR(s.advance(0.0, 0.0) - t2, 3.0 * 0.25 * before, 1e-12);
}

TEST(Schedule, ErrorToleranceIsValidated)
{
    AdaptiveParameters p;
    p.origin.path = "coupling.time";
    p.end = 10;
    p.errorTolerance = -1;
    try
    {
        p.validate();
        FAIL() << "negative error_tolerance accepted";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("coupling.time.error_tolerance"), std::string::npos);
    }
}

// A hit time closer than two steps ahead is reached in two equal steps, not in a full step and
// a sliver (48.9 s + 1.1 s before 50 s).
TEST(Schedule, HitTimeWithoutSliver)
{
    AdaptiveParameters p;
    p.end = 100;
    p.firstStep = 20;
    p.growthLimit = 1.45;
    p.targetChange = 1.0;
    p.hit = {50};
    auto made = makeSchedule(p, {});
    Schedule& s = *made;
    EXPECT_DOUBLE_EQ(s.advance(0.0), 20.0);
    // candidate step 20 * 1.45 = 29 < 30 to go, but 30 < 2 x 29: two steps of 15
    EXPECT_DOUBLE_EQ(s.advance(0.0), 35.0);
    EXPECT_DOUBLE_EQ(s.advance(0.0), 50.0);
}

// uniform: n dt up to end, the last step shorter; every full step is reported as exactly dt
// (the solid reuses its factorization only for a bitwise-equal dt).
TEST(Schedule, UniformStepsAreBitwiseConstant)
{
    UniformParameters p;
    p.dt = 0.1;
    p.end = 0.25 + 0.1 * 3; // 0.55: 5 full steps and one of 0.05
    Uniform s(p);
    EXPECT_EQ(s.plannedLevels(), 7);
    std::vector<double> steps;
    while (s.hasNext())
    {
        s.advance(0.0);
        steps.push_back(s.lastStep());
    }
    ASSERT_EQ(steps.size(), 6u);
    for (std::size_t i = 0; i < 5; ++i)
        EXPECT_EQ(steps[i], 0.1) << i; // exact, not 0.1 +- 1 ulp
    EXPECT_NEAR(steps[5], 0.05, 1e-12);
    EXPECT_DOUBLE_EQ(s.time(), 0.55);
}

// Every registered schedule builds itself from its keyword's defaults once the required keys
// are set, and describes itself by its keyword.
TEST(Schedule, RegistryListsEverySchedule)
{
    EXPECT_EQ(scheduleNames(),
              (std::vector<std::string>{"steady", "uniform", "list", "geometric", "adaptive"}));
    for (const auto& type : scheduleTypes())
    {
        ScheduleParameters p = type.defaults();
        EXPECT_EQ(p.type(), type.name);
        if (auto* u = p.get<UniformParameters>())
            *u = UniformParameters{u->origin, 1.0, 3.0};
        if (auto* l = p.get<ListParameters>())
            l->times = {0.0, 2.0};
        if (auto* g = p.get<GeometricParameters>())
        {
            g->end = 3.0;
            g->firstStep = 1.0;
        }
        if (auto* a = p.get<AdaptiveParameters>())
            a->end = 3.0;
        const auto s = makeSchedule(p, {10.0}); // adaptive: first step 1 s from tau = 10 s
        EXPECT_NE(s->describe().find(type.name), std::string::npos) << s->describe();
        EXPECT_EQ(s->time(), 0.0);
        Schedule& levels = *s;
        EXPECT_DOUBLE_EQ(allTimes(levels, 0.0).back(), type.name == "steady" ? 0.0
                                                       : type.name == "list" ? 2.0
                                                                             : 3.0)
            << type.name;
    }
}

// The adaptive rule is the same in both apps; a restart continues with the saved step.
TEST(Schedule, AdaptiveResumeUsesTheSavedStep)
{
    AdaptiveParameters p;
    p.end = 100;
    p.firstStep = 1;
    p.targetChange = 0.1;
    Adaptive a(p), b(p);
    a.advance(0.0);
    a.advance(0.1);  // factor 1: dt 1
    a.advance(0.05); // factor 2: dt 2, t = 4
    b.resume(a.level(), a.time(), a.lastStep());
    EXPECT_DOUBLE_EQ(a.advance(0.2), b.advance(0.2)); // factor 0.5: dt 1
    EXPECT_DOUBLE_EQ(b.time(), 5.0);
}
