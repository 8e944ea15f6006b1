// SPDX-License-Identifier: GPL-3.0-or-later
// SecantFluidModel (coupling.predictor: secant) with an affine "fluid" F(u) = f0 + J u of low
// rank and an affine "solid" S(F) = s0 + C F: once the samples' differences span the directions
// the fluid responds to (the row space of J), the predictor returns the coupled fixed point
// u* = S(F(u*)) exactly, wherever u* lies.
#include "driver/SecantFluidModel.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cstdio>
#include <map>
#include <optional>
#include <vector>

using fsi::driver::SecantFluidModel;

namespace
{
constexpr int kSize = 12; // interface vector length (4 nodes x 3)

struct AffineProblem
{
    Eigen::MatrixXd j, c;   // fluid Jacobian (rank 2), solid compliance
    Eigen::MatrixXd right;  // the directions of u the fluid responds to (row space of j)
    Eigen::VectorXd f0, s0; // affine parts
    int solves = 0;

    AffineProblem()
    {
        std::srand(7);
        const Eigen::MatrixXd left = Eigen::MatrixXd::Random(kSize, 2);
        right = Eigen::MatrixXd::Random(kSize, 2);
        j = 0.4 * left * right.transpose(); // the fluid responds to two directions only
        const Eigen::MatrixXd m = Eigen::MatrixXd::Random(kSize, kSize);
        c = 0.2 * (m * m.transpose() / kSize + Eigen::MatrixXd::Identity(kSize, kSize));
        f0 = Eigen::VectorXd::Random(kSize);
        s0 = Eigen::VectorXd::Random(kSize);
    }
    Eigen::VectorXd fluid(const Eigen::VectorXd& u) const { return f0 + j * u; }
    Eigen::VectorXd solid(const Eigen::VectorXd& f)
    {
        ++solves;
        return s0 + c * f;
    }
    // `count` fluid solves at the interfaces at() returns, the level accepted on the last.
    template <class Interface>
    void sampleLevel(SecantFluidModel& model, int count, Interface at) const
    {
        for (int i = 0; i < count; ++i)
        {
            const Eigen::VectorXd u = at();
            model.addSample(u, fluid(u));
        }
        model.acceptLevel();
    }
    std::optional<SecantFluidModel::Prediction> predict(SecantFluidModel& model,
                                                        const std::vector<int>& columns)
    {
        return model.predict(columns, [&](const Eigen::VectorXd& f) { return solid(f); });
    }
    // Level 0: three fluid solves at interfaces that differ in the fluid's two directions (and
    // nothing else), the last one accepted; returns the model's columns.
    std::vector<int> sampleBothDirections(SecantFluidModel& model)
    {
        const Eigen::VectorXd start = Eigen::VectorXd::Random(kSize);
        sampleLevel(model, 3,
                    [&] { return Eigen::VectorXd(start + right * Eigen::Vector2d::Random()); });
        return model.selectColumns();
    }
    // A level with one coupling iteration, a perturbation along the fluid's second direction,
    // then its accepted state (returned) at a random interface.
    Eigen::VectorXd sampleIteratedLevel(SecantFluidModel& model,
                                        double minPerturbationRms = 0.0) const
    {
        const Eigen::VectorXd start = Eigen::VectorXd::Random(kSize);
        const Eigen::VectorXd perturbed = start + 0.01 * right.col(1);
        for (const Eigen::VectorXd* u : {&perturbed, &start})
            model.addSample(*u, fluid(*u));
        model.acceptLevel(minPerturbationRms);
        return start;
    }
    Eigen::VectorXd fixedPoint() const
    {
        const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(kSize, kSize) - c * j;
        return a.fullPivLu().solve(s0 + c * f0);
    }
};
} // namespace

TEST(SecantFluidModel, ExactForAnAffineFluidOnceItsDirectionsAreSampled)
{
    AffineProblem p;
    SecantFluidModel model(3);
    const auto columns = p.sampleBothDirections(model);
    ASSERT_EQ(columns.size(), 2u);
    const auto prediction = p.predict(model, columns);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(prediction->columns, 2);
    EXPECT_EQ(prediction->solidSolves, 3);
    EXPECT_EQ(p.solves, 3);
    const Eigen::VectorXd exact = p.fixedPoint();
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-12 * exact.norm());
}

// The case's pattern: a level with a coupling iteration (its perturbation 1 % of the next
// level's creep step, in another direction), then a level accepted on its first solve. The
// older level's iteration is a column of its own perturbation (taken from that level's accepted
// state, not from the base): both directions are kept, and the prediction for the level after is
// the exact fixed point; with differences to the base, that column has 1 % new direction, below
// the 5 % filter, and the model would be one column. The pair's solid answers are solved once
// and kept: a second prediction needs no solve.
TEST(SecantFluidModel, AnOlderLevelsIterationKeepsItsDirectionBesideTheCreep)
{
    AffineProblem p;
    SecantFluidModel model(3);
    const Eigen::VectorXd start = p.sampleIteratedLevel(model);
    const Eigen::VectorXd crept = start + p.right.col(0);
    model.addSample(crept, p.fluid(crept));
    model.acceptLevel();
    const auto columns = model.selectColumns();
    ASSERT_EQ(columns.size(), 2u);
    const auto prediction = p.predict(model, columns);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(prediction->solidSolves, 3);
    const Eigen::VectorXd exact = p.fixedPoint();
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-10 * exact.norm());
    const auto again = p.predict(model, columns);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->solidSolves, 0);
    EXPECT_LT((again->displacement - exact).norm(), 1e-10 * exact.norm());
}

// A run of levels accepted on their first solve, longer than the memory: the newest level with
// a coupling iteration stays (its perturbation is the only second direction), the creep steps
// alone being parallel; the prediction is the exact fixed point. Levels without an iteration
// beyond the memory are still forgotten.
TEST(SecantFluidModel, KeepsTheNewestIterationBeyondItsMemory)
{
    AffineProblem p;
    SecantFluidModel model(3, 2);
    const Eigen::VectorXd start = p.sampleIteratedLevel(model);
    for (int level = 1; level <= 5; ++level)
        p.sampleLevel(model, 1, [&] { return Eigen::VectorXd(start + level * p.right.col(0)); });
    EXPECT_EQ(model.levels(), 4); // the newest, the two before it, and level 0
    const auto columns = model.selectColumns();
    ASSERT_EQ(columns.size(), 2u);
    const auto prediction = p.predict(model, columns);
    ASSERT_TRUE(prediction.has_value());
    const Eigen::VectorXd exact = p.fixedPoint();
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-10 * exact.norm());
}

// A perturbation below the noise floor (minPerturbationRms, the coupling tolerance in the driver)
// is not a direction: the older level with a real one is kept instead, and the model has both
// directions; counting the tiny one (floor 0) keeps it, drops the real one, and leaves one column.
TEST(SecantFluidModel, ANoiseLevelIterationDoesNotReplaceARealPerturbation)
{
    const double floor = 1e-6; // [m], |v|/sqrt(n)
    std::map<double, std::size_t> columnsByFloor;
    for (const double minPerturbationRms : {floor, 0.0})
    {
        AffineProblem p;
        SecantFluidModel model(3, 2);
        const Eigen::VectorXd start = p.sampleIteratedLevel(model, minPerturbationRms);
        const Eigen::VectorXd step = start + p.right.col(0);
        const Eigen::VectorXd noise = step + 1e-9 * p.right.col(1);
        for (const Eigen::VectorXd* u : {&noise, &step})
            model.addSample(*u, p.fluid(*u));
        model.acceptLevel(minPerturbationRms);
        for (int level = 2; level <= 5; ++level)
        {
            const Eigen::VectorXd u = start + level * p.right.col(0);
            model.addSample(u, p.fluid(u));
            model.acceptLevel(minPerturbationRms);
        }
        const auto columns = model.selectColumns(SecantFluidModel::Base::Accepted, floor);
        columnsByFloor[minPerturbationRms] = columns.size();
        if (minPerturbationRms > 0.0)
        {
            const auto prediction = p.predict(model, columns);
            ASSERT_TRUE(prediction.has_value());
            const Eigen::VectorXd exact = p.fixedPoint();
            EXPECT_LT((prediction->displacement - exact).norm(), 1e-10 * exact.norm());
        }
    }
    EXPECT_EQ(columnsByFloor[floor], 2u);
    EXPECT_EQ(columnsByFloor[0.0], 1u);
}

// With the solid's linear response (respond: A W for the load changes W, here A = C), the
// columns cost no solve: one solve for the base, one respond() call for all columns, and the
// same exact fixed point. Those answers are not kept: a second prediction asks again.
TEST(SecantFluidModel, ColumnsFromTheSolidsLinearResponse)
{
    AffineProblem p;
    SecantFluidModel model(3);
    const Eigen::VectorXd start = Eigen::VectorXd::Random(kSize);
    Eigen::VectorXd accepted; // the level's last (accepted) interface
    p.sampleLevel(model, 3,
                  [&]
                  {
                      accepted = start + p.right * Eigen::Vector2d::Random();
                      return accepted;
                  });
    const auto columns = model.selectColumns();
    ASSERT_EQ(columns.size(), 2u);
    int responds = 0;
    const SecantFluidModel::SolidResponse respond = [&](const Eigen::MatrixXd& w)
    {
        ++responds;
        EXPECT_EQ(w.cols(), 2);
        return Eigen::MatrixXd(p.c * w);
    };
    const auto solve = [&](const Eigen::VectorXd& f) { return p.solid(f); };
    const auto prediction =
        model.predict(columns, solve, SecantFluidModel::Base::Accepted, respond);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(prediction->solidSolves, 1);
    EXPECT_EQ(prediction->responseColumns, 2);
    EXPECT_EQ(p.solves, 1);
    EXPECT_EQ(responds, 1);
    const Eigen::VectorXd exact = p.fixedPoint();
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-12 * exact.norm());

    // a response 1 % off (a loose linear solve) moves the prediction by about that much of
    // the coupled correction, not more
    const SecantFluidModel::SolidResponse rough = [&](const Eigen::MatrixXd& w)
    { return Eigen::MatrixXd(1.01 * p.c * w); };
    const auto again = model.predict(columns, solve, SecantFluidModel::Base::Accepted, rough);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->solidSolves, 0); // the base's answer is kept
    EXPECT_EQ(again->responseColumns, 2);
    // the coupled correction: from the solid under the accepted loads to the fixed point
    const double correction = (exact - (p.s0 + p.c * p.fluid(accepted))).norm();
    EXPECT_GT((again->displacement - exact).norm(), 1e-6 * correction);
    EXPECT_LT((again->displacement - exact).norm(), 0.05 * correction);
}

// The base solve and the response columns in one call (solveAndRespond: the solid's
// solveWithResponse): used instead of solve() + respond() for the base, the same prediction.
TEST(SecantFluidModel, BaseSolveAndColumnsInOneCall)
{
    AffineProblem p;
    SecantFluidModel model(3);
    const auto columns = p.sampleBothDirections(model);
    ASSERT_EQ(columns.size(), 2u);
    int responds = 0, together = 0;
    const SecantFluidModel::SolidResponse respond = [&](const Eigen::MatrixXd& w)
    {
        ++responds;
        return Eigen::MatrixXd(p.c * w);
    };
    const SecantFluidModel::SolidSolveWithResponse solveAndRespond =
        [&](const Eigen::VectorXd& f, const Eigen::MatrixXd& w)
    {
        ++together;
        EXPECT_EQ(w.cols(), 2);
        return std::make_pair(p.solid(f), Eigen::MatrixXd(p.c * w));
    };
    const auto solve = [&](const Eigen::VectorXd& f) { return p.solid(f); };
    const auto prediction =
        model.predict(columns, solve, SecantFluidModel::Base::Accepted, respond, solveAndRespond);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(together, 1);
    EXPECT_EQ(responds, 0);
    EXPECT_EQ(p.solves, 1); // the one inside solveAndRespond
    EXPECT_EQ(prediction->solidSolves, 1);
    EXPECT_EQ(prediction->responseColumns, 2);
    const Eigen::VectorXd exact = p.fixedPoint();
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-12 * exact.norm());
    // the base's answer is kept: a second prediction of the level needs respond() alone
    const auto again =
        model.predict(columns, solve, SecantFluidModel::Base::Accepted, respond, solveAndRespond);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(together, 1);
    EXPECT_EQ(responds, 1);
    EXPECT_LT((again->displacement - exact).norm(), 1e-12 * exact.norm());
}

// With one sampled direction only the component of the fluid's answer along it is modelled: the
// prediction is not exact, and solve() is called once per column plus once.
TEST(SecantFluidModel, OneColumnModelsOneDirection)
{
    AffineProblem p;
    SecantFluidModel model(1);
    p.sampleLevel(model, 3, [] { return Eigen::VectorXd(Eigen::VectorXd::Random(kSize)); });
    const auto columns = model.selectColumns();
    ASSERT_EQ(columns.size(), 1u);
    const auto prediction = p.predict(model, columns);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(p.solves, 2);
    EXPECT_GT((prediction->displacement - p.fixedPoint()).norm(), 1e-6);
}

// The feedback margin is the smallest singular value of I - V^+ Z. With one column v and a
// fluid and solid that answer a change along v with g times it (Z = g V), it is |1 - g|: a gain
// of 0.995 (a structure near static divergence) leaves 0.005, and the prediction is still the
// exact fixed point, 1 / (1 - g) = 200 times the frozen-loads step.
TEST(SecantFluidModel, FeedbackMarginIsOneMinusTheGainAlongAColumn)
{
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(kSize, 3);
    const double gain = 0.995;
    const Eigen::VectorXd s0 = 1e-3 * Eigen::VectorXd::Ones(kSize);
    const auto fluid = [&](const Eigen::VectorXd& u) -> Eigen::VectorXd
    { return gain * e * e.dot(u); }; // load along e, proportional to the deflection along e
    const auto solid = [&](const Eigen::VectorXd& f) -> Eigen::VectorXd { return s0 + f; };
    SecantFluidModel model(1);
    for (const double a : {0.0, 2e-3})
    {
        const Eigen::VectorXd u = a * e;
        model.addSample(u, fluid(u));
    }
    model.acceptLevel();
    const auto prediction = model.predict(model.selectColumns(), solid);
    ASSERT_TRUE(prediction.has_value());
    EXPECT_NEAR(prediction->feedbackMargin, 1.0 - gain, 1e-12);
    Eigen::VectorXd exact = s0;
    exact(3) = s0(3) / (1.0 - gain); // u = s0 + g e (e.u)
    EXPECT_LT((prediction->displacement - exact).norm(), 1e-10 * exact.norm());
}

// No accepted level, or a single sample: no columns, no prediction, no solid solve.
TEST(SecantFluidModel, NoColumnsWithoutTwoSamples)
{
    AffineProblem p;
    SecantFluidModel model(3);
    EXPECT_TRUE(model.selectColumns().empty());
    const Eigen::VectorXd u = Eigen::VectorXd::Random(kSize);
    model.addSample(u, p.fluid(u));
    EXPECT_TRUE(model.selectColumns().empty()); // not accepted yet
    model.acceptLevel();
    EXPECT_TRUE(model.selectColumns().empty());
    EXPECT_FALSE(p.predict(model, {}));
    EXPECT_EQ(p.solves, 0);
}

// Samples of levels older than maxLevels are forgotten.
TEST(SecantFluidModel, ForgetsLevelsBeyondItsMemory)
{
    AffineProblem p;
    SecantFluidModel model(5, 1);
    for (int level = 0; level < 4; ++level)
        p.sampleLevel(model, 1, [] { return Eigen::VectorXd(Eigen::VectorXd::Random(kSize)); });
    EXPECT_EQ(model.levels(), 2); // the newest and one older level
    EXPECT_EQ(model.selectColumns().size(), 1u);
}

// Restart: a model loaded from save() predicts exactly what the saved one predicts, also after
// more samples; a state that does not fit the interface size is refused with an error.
TEST(SecantFluidModel, SaveAndLoadRestoreThePredictor)
{
    AffineProblem p;
    SecantFluidModel model(3);
    for (int level = 0; level < 3; ++level)
        p.sampleLevel(model, 2, [] { return Eigen::VectorXd(Eigen::VectorXd::Random(kSize)); });
    SecantFluidModel restored(3);
    restored.load(model.save(), kSize);
    EXPECT_EQ(restored.levels(), model.levels());
    const Eigen::VectorXd u = Eigen::VectorXd::Random(kSize);
    for (SecantFluidModel* m : {&model, &restored})
        p.sampleLevel(*m, 1, [&] { return u; });
    ASSERT_EQ(restored.selectColumns(), model.selectColumns());
    const auto a = p.predict(model, model.selectColumns());
    const auto b = p.predict(restored, restored.selectColumns());
    ASSERT_TRUE(a && b);
    EXPECT_EQ((a->displacement - b->displacement).norm(), 0.0);

    auto damaged = model.save();
    damaged.values.pop_back();
    EXPECT_THROW(restored.load(damaged, kSize), std::runtime_error);
    EXPECT_THROW(restored.load(model.save(), kSize + 3), std::runtime_error);
}

// Coupling iterations with the model (Base::Newest): each fluid solve is a sample, the solid's
// answer to it is kept (setNewestResponse), and the next iterate solves the solid coupled to the
// model. On the affine problem, whose plain fixed-point iteration diverges (the fluid's feedback
// is stronger than the solid), the iteration reaches the fixed point to round-off within a few
// fluid solves, and its steps call the solid for no sample of the level (only setNewestResponse).
// Observed: 4 fluid solves to |u - u*| < 1e-10 |u*|.
TEST(SecantFluidModel, CouplingIterationsReachTheFixedPointWithoutExtraSolidSolves)
{
    AffineProblem p;
    // strong feedback: the spectral radius of the loop S'F' = c j is 1.5
    p.j *= 1.5 / Eigen::EigenSolver<Eigen::MatrixXd>(p.c * p.j).eigenvalues().cwiseAbs().maxCoeff();
    const Eigen::VectorXd exact = p.fixedPoint();
    {
        // plain fixed-point iteration u <- S(F(u)) diverges here
        Eigen::VectorXd u = Eigen::VectorXd::Zero(kSize);
        for (int i = 0; i < 20; ++i)
            u = p.solid(p.fluid(u));
        ASSERT_GT((u - exact).norm(), 10 * exact.norm());
        p.solves = 0;
    }
    SecantFluidModel model(kSize);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(kSize);
    int fluidSolves = 0;
    int modelSolidSolves = 0;
    for (; fluidSolves < 12 && (u - exact).norm() > 1e-10 * exact.norm(); ++fluidSolves)
    {
        const Eigen::VectorXd force = p.fluid(u);
        model.addSample(u, force);
        const Eigen::VectorXd output = p.solid(force);
        model.setNewestResponse(output);
        const auto columns = model.selectColumns(SecantFluidModel::Base::Newest);
        const auto step = model.predict(
            columns, [&](const Eigen::VectorXd& f) { return p.solid(f); },
            SecantFluidModel::Base::Newest);
        if (step)
            modelSolidSolves += step->solidSolves;
        u = step ? step->displacement : Eigen::VectorXd(0.5 * (u + output));
    }
    std::printf("secant coupling iterations: %d fluid solves, error %.1e\n", fluidSolves,
                (u - exact).norm() / exact.norm());
    EXPECT_LE(fluidSolves, 6);
    EXPECT_LT((u - exact).norm(), 1e-10 * exact.norm());
    EXPECT_EQ(modelSolidSolves, 0);
    EXPECT_EQ(p.solves, fluidSolves);

    // A new level (the solid's operator changed): the kept answers are forgotten, and a step
    // then solves the solid once for the base and once per column.
    model.acceptLevel();
    model.clearResponses();
    const auto columns = model.selectColumns();
    ASSERT_FALSE(columns.empty());
    const auto prediction =
        model.predict(columns, [&](const Eigen::VectorXd& f) { return p.solid(f); });
    ASSERT_TRUE(prediction.has_value());
    EXPECT_EQ(prediction->solidSolves, 1 + static_cast<int>(columns.size()));
}

// Columns closer to the base than minColumnRms (|v|/sqrt(n)) are noise of the fluid's accuracy,
// not directions: they are not selected.
TEST(SecantFluidModel, ColumnsBelowTheNoiseFloorAreNotSelected)
{
    AffineProblem p;
    SecantFluidModel model(4);
    const Eigen::VectorXd u = Eigen::VectorXd::Random(kSize);
    const Eigen::VectorXd far = u + 1e-3 * Eigen::VectorXd::Random(kSize);
    const Eigen::VectorXd near = u + 1e-9 * Eigen::VectorXd::Random(kSize);
    for (const Eigen::VectorXd* x : {&far, &near, &u})
        model.addSample(*x, p.fluid(*x));
    EXPECT_EQ(model.selectColumns(SecantFluidModel::Base::Newest).size(), 2u);
    const auto kept = model.selectColumns(SecantFluidModel::Base::Newest, 1e-6);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0], 2); // far (samples are newest first: u, near, far)
}
