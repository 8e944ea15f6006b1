// SPDX-License-Identifier: GPL-3.0-or-later
//
// A linear model of the fluid's answer to the interface shape, learnt from accepted levels, and
// the level predictor built on it (coupling.predictor: secant).
//
// The quasi-steady loads depend on time only through the interface: between accepted levels
// n-j and n the fluid force changed by F_n - F_{n-j} because the interface moved by
// u_n - u_{n-j}. With those differences as the columns of V (displacements) and W (forces),
//   F(u) ~ F_n + W c,   c = argmin |V c - (u - u_n)|      (a secant model, zero response off
//                                                          the span of V)
// The predictor solves the solid at the new time coupled to that model. The solid is affine in
// its loads at a fixed level (small strain, law linear in the strain): u(c) = b + Z c with
// b = S(F_n), Z_i = S(F_n + W_i) - b, so c solves the small system (I - V^+ Z) c = V^+ (b - u_n).
// It costs 1 + columns solid re-solves and no fluid solve. Where the loads do not depend on the
// interface, or depend on it linearly within the span of V, it is the level's exact solution.
#pragma once

#include <Eigen/Core>

#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace fsi::driver
{

class SecantFluidModel
{
public:
    // maxColumns >= 1: differences to at most that many older levels are kept.
    explicit SecantFluidModel(int maxColumns = 4, int maxLevels = 3);

    // Adds a fluid solve of the current level: its interface input u [m] and the nodal fluid
    // force F [N] it answered with (3 per wetted node, the same size every call).
    void addSample(const Eigen::VectorXd& u, const Eigen::VectorXd& force);
    // The current level was accepted on its last sample; older levels beyond maxLevels drop out.
    void acceptLevel();
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

    struct Prediction
    {
        Eigen::VectorXd displacement; // the coupled first iterate [m]
        int columns = 0;              // secant columns used
        int solidSolves = 0;
    };
    // The older levels whose differences are usable columns (indices 1.. into the stored levels,
    // newest first): nearly parallel steps are dropped. Empty when fewer than two levels are
    // known. A distributed caller takes rank 0's choice, so that every rank solves equally often.
    std::vector<int> selectColumns() const;
    // Calls solve() 1 + columns.size() times (none when columns is empty). Returns nullopt when
    // columns is empty or the model is degenerate (I - V^+ Z singular: the coupled model has no
    // unique state, e.g. past static divergence).
    std::optional<Prediction> predict(const std::vector<int>& columns,
                                      const SolidSolve& solve) const;

private:
    int base() const; // index of the newest accepted sample (-1: none)
    Eigen::MatrixXd differences(const std::vector<int>& others, bool forces) const;

    int maxColumns_, maxLevels_;
    struct Sample
    {
        Eigen::VectorXd u, force;
        int level = 0;         // counts accepted levels
        bool accepted = false; // the level's accepted state
    };
    std::deque<Sample> samples_; // newest first
    int currentLevel_ = 0;
    // candidate columns: indices into samples_ (accepted states first, newest first)
    std::vector<int> candidates() const;
};

} // namespace fsi::driver
