// SPDX-License-Identifier: GPL-3.0-or-later
//
// A linear model of the fluid's answer to the interface shape, learnt from past fluid solves,
// the level predictor built on it (coupling.predictor: secant) and the coupling iterations built
// on it (coupling.secant.coupling_iterations: true).
//
// The quasi-steady loads depend on time only through the interface. Each fluid solve is a sample
// (interface input u_s [m], nodal loads F_s [N]). The base is the last accepted level's final
// solve (u_n, F_n); the columns of V and W are the differences u_r - u_s and F_r - F_s of the
// other samples of that level and of the maxLevels levels before it (accepted states first,
// then the coupling iterations, newest first; a column with less than 5 % of new direction
// (QR filter) is dropped; at most maxColumns). The reference r is the base, except for a coupling
// iteration of an older level: there it is that level's accepted state, so that the column is
// the iteration's own perturbation, not the creep since that level plus it (a perturbation 20
// times smaller than that creep fails the 5 % filter, and a level accepted on its first solve
// then leaves the next predictor a one-column model). All kept, both choices span the same space:
//   F(u) ~ F_n + W c,   c = argmin |V c - (u - u_n)|      (a secant model, zero response off
//                                                          the span of V)
// The level differences alone do not do: a level's step mixes the bending that the load change
// causes with the twist that causes it, and a model from those steps sees a spurious feedback
// loop of gain ~1 (cases/hydrofoil/README.md); the coupling iterations perturb the interface in
// other mixes. The predictor solves the solid at the new time coupled to the model. The solid
// is affine in its loads at a fixed level (small strain, law linear in the strain): u(c) = b + Z c
// with b = S(F_n), Z_i = S(F_n + W_i) - b, so c solves the small system
// (I - V^+ Z) c = V^+ (b - u_n). It costs 1 + columns solid re-solves and no fluid solve, or, with
// respond (Z = A W, the solid's linear response), one solve and one linear solve per column. Where
// the loads depend on the interface linearly within the span of V, it is the level's exact
// coupled solution.
#pragma once

#include <Eigen/Core>

#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace fsi::driver
{

// `coupling.secant` (config/coupled.example.yaml): the model's memory, and whether the coupling
// iterations use it.
struct SecantParameters
{
    int maxColumns = 4;              // columns used at most (>= 1)
    int levels = 3;                  // older levels whose solves are kept (>= 1)
    bool couplingIterations = false; // every coupling iteration steps with the model
    // The predictor's column answers A W_j: linear solves to this relative residual with the
    // level's tangent, no residual assembly (a solid linear in its loads); 0: a full solid
    // re-solve per column (exact). In [0, 0.1].
    double responseTolerance = 1e-2;
    // A model whose feedback margin (Prediction::feedbackMargin) is below this amplifies the
    // frozen-loads step more than 1/margin-fold: not trusted (the predictor falls back to the
    // linear extrapolation, a coupling iteration to the accelerator's iterate). In [0, 1);
    // 0 = always trusted.
    double minFeedbackMargin = 0.0;
};

class SecantFluidModel
{
public:
    // maxColumns >= 1: columns used at most; maxLevels >= 1: older levels whose samples are kept
    // besides the last accepted one.
    explicit SecantFluidModel(int maxColumns = 4, int maxLevels = 3);

    // The sample the model is expanded about: the last accepted level's final solve (the level
    // predictor) or the newest solve (a coupling iteration).
    enum class Base
    {
        Accepted,
        Newest
    };

    // Adds a fluid solve of the current level: its interface input u [m] and the nodal fluid
    // force F [N] it answered with (3 per wetted node, the same size every call).
    void addSample(const Eigen::VectorXd& u, const Eigen::VectorXd& force);
    // The solid's interface displacement under the newest sample's force at the current level
    // (the coupling iteration's solid output), kept for the model's steps. Pre: a sample exists.
    void setNewestResponse(const Eigen::VectorXd& displacement);
    // Forgets the solid's answers: call whenever the solid's operator changes (each attempt at a
    // level, since a retried level may have another dt).
    void clearResponses();
    // The current level was accepted on its last sample; older levels beyond maxLevels drop out,
    // except the newest level with a coupling iteration while none within maxLevels has one (a
    // run of levels accepted on their first solve would otherwise leave a model of the levels'
    // steps alone: one column, all of them nearly parallel). An iteration whose interface differs
    // from its level's accepted one by less than minPerturbationRms [m] (|v|/sqrt(n)) does not
    // count: noise of the fluid's accuracy, not a direction (pass selectColumns' minColumnRms).
    void acceptLevel(double minPerturbationRms = 0.0);
    void clear();
    int levels() const; // accepted levels held

    // Restart: the samples, newest first: meta = {currentLevel, then per sample its level and
    // accepted flag}, values = per sample u then F. load() throws std::runtime_error when they
    // do not fit together or the interface size n.
    struct State
    {
        std::vector<int> meta;
        std::vector<double> values;
    };
    State save() const;
    void load(const State& state, int n);

    // The solid's interface displacement under the given nodal loads at the new level
    // (collective when the solid is distributed). Throws std::runtime_error when it fails.
    using SolidSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd& loads)>;
    // The solid's interface displacement change under nodal load changes (one per column) at
    // the new level, to predictor accuracy: the solid's linear response A W (collective when
    // the solid is distributed). Throws std::runtime_error when it fails.
    using SolidResponse = std::function<Eigen::MatrixXd(const Eigen::MatrixXd& loadChanges)>;
    // solve(loads) and respond(loadChanges) in one call (the solid's solve with its linear
    // responses riding along: fe::StructuralSolver::solveWithResponse).
    using SolidSolveWithResponse = std::function<std::pair<Eigen::VectorXd, Eigen::MatrixXd>(
        const Eigen::VectorXd& loads, const Eigen::MatrixXd& loadChanges)>;

    struct Prediction
    {
        Eigen::VectorXd displacement; // the coupled first iterate [m]
        int columns = 0;              // secant columns used
        int solidSolves = 0;          // solve() calls
        int responseColumns = 0;      // columns answered by respond() (no solve)
        // smallest singular value of I - V^+ Z (in the columns' own scaling): small when the
        // model's gain nears 1 along some mix of its columns, or when nearly parallel columns
        // make V^+ large; either way the prediction amplifies the frozen-loads step, and the
        // samples' noise, up to 1/feedbackMargin-fold
        double feedbackMargin = 1.0;
    };
    // The samples whose differences (to the base or their level's accepted state) are usable
    // columns (indices into the stored samples, newest first): nearly parallel ones (less than
    // 5 % new direction) and those whose interface differs from that reference's by less than
    // minColumnRms [m] (|v|/sqrt(n): noise of the fluid's accuracy, not a direction) are dropped.
    // Empty when there is no base or no other sample. A distributed caller takes rank 0's choice,
    // so that every rank solves equally often.
    std::vector<int> selectColumns(Base base = Base::Accepted, double minColumnRms = 0.0) const;
    // The coupled state of the solid and the model. Calls solve() for the base and each column
    // whose answer at this level is not known yet (at most 1 + columns.size() times; none when
    // columns is empty). With respond (the solid linear in its loads), the unknown columns are
    // answered by one respond() call instead of a solve() each: Z = A W to respond's accuracy,
    // a predictor's, so those answers are not kept for later steps; with solveAndRespond as
    // well, a base solve and that respond() call are one solveAndRespond() call. Returns
    // nullopt when columns is empty or the model is degenerate (I - V^+ Z singular: the coupled
    // model has no unique state, e.g. past static divergence).
    std::optional<Prediction> predict(const std::vector<int>& columns, const SolidSolve& solve,
                                      Base base = Base::Accepted, const SolidResponse& respond = {},
                                      const SolidSolveWithResponse& solveAndRespond = {});

private:
    int base(Base which) const; // index of the base sample (-1: none)
    // Index of the given level's accepted sample (-1: none held).
    int acceptedOf(int level) const;
    // The sample a column's difference is taken from (header comment): the accepted state of an
    // older level's coupling iteration, else `base`.
    int reference(int sample, int base) const;
    // Whether u_from - u_to is a direction, not noise: nonzero and |.|/sqrt(n) >= minColumnRms.
    bool isDirection(int from, int to, double minColumnRms) const;
    Eigen::MatrixXd differences(int base, const std::vector<int>& others, bool forces) const;

    int maxColumns_, maxLevels_;
    struct Sample
    {
        Eigen::VectorXd u, force;
        int level = 0;         // counts accepted levels
        bool accepted = false; // the level's accepted state
        // the solid's answer S(force) at the current level [m]; empty: unknown
        Eigen::VectorXd response;
    };
    std::deque<Sample> samples_; // newest first
    int currentLevel_ = 0;
    // candidate columns: indices into samples_ other than the base (the current level's solves,
    // then accepted states, then the older levels' other solves; newest first within each)
    std::vector<int> candidates(int base) const;
};

} // namespace fsi::driver
