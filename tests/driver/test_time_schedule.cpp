// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/TimeSchedule.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

using namespace fsi::driver;

namespace
{
std::vector<double> allTimes(TimeSchedule s, double change = 0.01)
{
    std::vector<double> t{s.time()};
    while (s.hasNext())
        t.push_back(s.advance(change));
    return t;
}
} // namespace

TEST(TimeSchedule, SteadyIsOneInstantaneousLevel)
{
    TimeSchedule s({}, {});
    EXPECT_EQ(allTimes(s), std::vector<double>{0.0});
    EXPECT_EQ(s.plannedLevels(), 1);
}

TEST(TimeSchedule, GeometricLandsOnHitTimesAndEnd)
{
    TimeScheduleParameters p;
    p.type = "geometric";
    p.end = 3600;
    p.firstStep = 1;
    p.growth = 2;
    p.maxStep = 600;
    p.hit = {50, 360};
    const auto t = allTimes(TimeSchedule(p, {}));
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

TEST(TimeSchedule, AdaptiveStartsFromTheShortestRelaxationTimeAndFollowsTheChange)
{
    TimeScheduleParameters p;
    p.type = "adaptive";
    p.end = 100;
    p.targetChange = 0.02;
    p.growthLimit = 2;
    p.shrinkLimit = 0.5;
    p.hit = {50};
    TimeSchedule s(p, {4.13, 81.95, 1610});
    EXPECT_DOUBLE_EQ(s.advance(0.0), 0.413);            // first step = min tau / 10
    EXPECT_DOUBLE_EQ(s.advance(0.04), 0.413 + 0.2065);  // change 2x target: halve
    EXPECT_NEAR(s.advance(0.001), 0.6195 + 0.413, 1e-12); // small change: growth limit 2
    std::vector<double> t;
    while (s.hasNext())
        t.push_back(s.advance(0.001));
    EXPECT_NE(std::find(t.begin(), t.end(), 50.0), t.end());
    EXPECT_DOUBLE_EQ(t.back(), 100.0);
    EXPECT_FALSE(s.hasNext());
}

TEST(TimeSchedule, InvalidParametersNameTheKey)
{
    TimeScheduleParameters p;
    p.type = "list";
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
    p.type = "adaptive";
    p.end = 10;
    EXPECT_THROW(TimeSchedule(p, {}), std::runtime_error); // elastic: first_step required
}

// Restart: resuming after level 2 of a list gives the remaining planned times.
TEST(TimeSchedule, ResumeContinuesWithThePlannedTimes)
{
    TimeScheduleParameters p;
    p.type = "list";
    p.times = {0, 1, 2, 5, 10};
    TimeSchedule s(p, {});
    s.resume(2, 2.0, 1.0);
    EXPECT_EQ(s.level(), 2);
    EXPECT_EQ(allTimes(s), (std::vector<double>{2, 5, 10}));
}

// The time-step cure inserts a shorter level and keeps the planned time as the next one.
TEST(TimeSchedule, CutStepInsertsAShorterLevel)
{
    TimeScheduleParameters p;
    p.type = "list";
    p.times = {0, 4, 8};
    TimeSchedule s(p, {});
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
TEST(TimeSchedule, AdaptiveStepFollowsThePathError)
{
    TimeScheduleParameters p;
    p.type = "adaptive";
    p.end = 1000;
    p.firstStep = 1;
    p.targetChange = 0.1;
    p.errorTolerance = 1e-3;
    p.growthLimit = 3;
    p.shrinkLimit = 0.25;
    TimeSchedule s(p, {});
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

TEST(TimeSchedule, ErrorToleranceIsValidated)
{
    TimeScheduleParameters p;
    p.type = "adaptive";
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
TEST(TimeSchedule, HitTimeWithoutSliver)
{
    TimeScheduleParameters p;
    p.type = "adaptive";
    p.end = 100;
    p.firstStep = 20;
    p.growthLimit = 1.45;
    p.targetChange = 1.0;
    p.hit = {50};
    TimeSchedule s(p, {});
    EXPECT_DOUBLE_EQ(s.advance(0.0), 20.0);
    // candidate step 20 * 1.45 = 29 < 30 to go, but 30 < 2 x 29: two steps of 15
    EXPECT_DOUBLE_EQ(s.advance(0.0), 35.0);
    EXPECT_DOUBLE_EQ(s.advance(0.0), 50.0);
}
