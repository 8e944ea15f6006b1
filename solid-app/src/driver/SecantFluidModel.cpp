// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/SecantFluidModel.hpp"

#include "acceleration/QrFilter.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace fsi::driver
{

namespace
{
// A difference column with less than this fraction of new direction is dropped (two samples
// whose differences to the base point the same way carry no second direction, only noise).
constexpr double kColumnFilter = 0.05;
} // namespace

SecantFluidModel::SecantFluidModel(int maxColumns, int maxLevels)
    : maxColumns_(maxColumns), maxLevels_(maxLevels)
{
    if (maxColumns < 1 || maxLevels < 1)
        throw std::logic_error("SecantFluidModel: maxColumns and maxLevels must be >= 1");
}

void SecantFluidModel::addSample(const Eigen::VectorXd& u, const Eigen::VectorXd& force)
{
    if (u.size() != force.size() || (!samples_.empty() && u.size() != samples_[0].u.size()))
        throw std::logic_error("SecantFluidModel: interface vectors of different sizes");
    samples_.push_front({u, force, currentLevel_, false, Eigen::VectorXd()});
}

void SecantFluidModel::acceptLevel(double minPerturbationRms)
{
    if (samples_.empty() || samples_[0].level != currentLevel_)
        return;
    samples_[0].accepted = true;
    ++currentLevel_;
    // Levels older than the memory drop out, except the newest one with a coupling iteration
    // when no level within the memory has one: its perturbation stays a column.
    const int oldest = currentLevel_ - 1 - maxLevels_; // the oldest level kept
    int perturbed = -1; // the newest level with a coupling iteration besides its accepted state
    for (int i = 0; i < static_cast<int>(samples_.size()) && perturbed < 0; ++i)
    {
        const int accepted = samples_[i].accepted ? -1 : acceptedOf(samples_[i].level);
        if (accepted >= 0 && isDirection(accepted, i, minPerturbationRms))
            perturbed = samples_[i].level;
    }
    const int keep = perturbed < oldest ? perturbed : -1;
    samples_.erase(std::remove_if(samples_.begin(), samples_.end(),
                                  [&](const Sample& s)
                                  { return s.level < oldest && s.level != keep; }),
                   samples_.end());
}

void SecantFluidModel::setNewestResponse(const Eigen::VectorXd& displacement)
{
    if (samples_.empty() || displacement.size() != samples_[0].u.size())
        throw std::logic_error("SecantFluidModel: a response needs its sample, of the same size");
    samples_[0].response = displacement;
}

void SecantFluidModel::clearResponses()
{
    for (auto& s : samples_)
        s.response.resize(0);
}

void SecantFluidModel::clear()
{
    samples_.clear();
}

SecantFluidModel::State SecantFluidModel::save() const
{
    State state;
    state.meta.push_back(currentLevel_);
    for (const auto& sample : samples_)
    {
        state.meta.push_back(sample.level);
        state.meta.push_back(sample.accepted ? 1 : 0);
        state.values.insert(state.values.end(), sample.u.data(), sample.u.data() + sample.u.size());
        state.values.insert(state.values.end(), sample.force.data(),
                            sample.force.data() + sample.force.size());
    }
    return state;
}

void SecantFluidModel::load(const State& state, int n)
{
    const std::size_t count = state.meta.empty() ? 0 : (state.meta.size() - 1) / 2;
    if (state.meta.empty() || state.meta.size() != 1 + 2 * count ||
        state.values.size() != 2 * count * static_cast<std::size_t>(n))
        throw std::runtime_error("the secant predictor's samples do not fit an interface of " +
                                 std::to_string(n / 3) + " nodes");
    clear();
    currentLevel_ = state.meta[0];
    const double* data = state.values.data();
    for (std::size_t i = 0; i < count; ++i, data += 2 * n)
        samples_.push_back({Eigen::Map<const Eigen::VectorXd>(data, n),
                            Eigen::Map<const Eigen::VectorXd>(data + n, n), state.meta[1 + 2 * i],
                            state.meta[2 + 2 * i] != 0, Eigen::VectorXd()});
}

int SecantFluidModel::levels() const
{
    int count = 0;
    for (const auto& s : samples_)
        count += s.accepted ? 1 : 0;
    return count;
}

int SecantFluidModel::base(Base which) const
{
    if (which == Base::Newest)
        return samples_.empty() ? -1 : 0;
    for (std::size_t i = 0; i < samples_.size(); ++i)
        if (samples_[i].accepted)
            return static_cast<int>(i);
    return -1;
}

std::vector<int> SecantFluidModel::candidates(int base) const
{
    std::vector<int> current, accepted, others;
    for (int i = 0; i < static_cast<int>(samples_.size()); ++i)
    {
        if (i == base)
            continue;
        const Sample& s = samples_[i];
        (s.level == currentLevel_ ? current : s.accepted ? accepted : others).push_back(i);
    }
    current.insert(current.end(), accepted.begin(), accepted.end());
    current.insert(current.end(), others.begin(), others.end());
    return current;
}

int SecantFluidModel::acceptedOf(int level) const
{
    for (int i = 0; i < static_cast<int>(samples_.size()); ++i)
        if (samples_[i].accepted && samples_[i].level == level)
            return i;
    return -1;
}

int SecantFluidModel::reference(int sample, int base) const
{
    const Sample& s = samples_[sample];
    const int accepted = s.accepted || s.level >= currentLevel_ ? -1 : acceptedOf(s.level);
    return accepted >= 0 ? accepted : base;
}

bool SecantFluidModel::isDirection(int from, int to, double minColumnRms) const
{
    const Eigen::VectorXd& u = samples_[from].u;
    const double distance = (u - samples_[to].u).norm();
    return distance > 0.0 && distance >= minColumnRms * std::sqrt(static_cast<double>(u.size()));
}

Eigen::MatrixXd SecantFluidModel::differences(int base, const std::vector<int>& others,
                                              bool forces) const
{
    Eigen::MatrixXd d(samples_[base].u.size(), static_cast<Eigen::Index>(others.size()));
    for (std::size_t j = 0; j < others.size(); ++j)
    {
        const Sample& from = samples_[reference(others[j], base)];
        const Sample& to = samples_[others[j]];
        d.col(static_cast<Eigen::Index>(j)) =
            forces ? Eigen::VectorXd(from.force - to.force) : Eigen::VectorXd(from.u - to.u);
    }
    return d;
}

std::vector<int> SecantFluidModel::selectColumns(Base which, double minColumnRms) const
{
    const int b = base(which);
    if (b < 0)
        return {};
    std::vector<int> all;
    for (int i : candidates(b))
        if (isDirection(reference(i, b), i, minColumnRms))
            all.push_back(i);
    if (all.empty())
        return {};
    const auto qr = acceleration::filteredQr(differences(b, all, false), kColumnFilter,
                                             acceleration::QrFilterKind::Column);
    std::vector<int> kept;
    for (int i : qr.kept)
        if (static_cast<int>(kept.size()) < maxColumns_)
            kept.push_back(all[i]);
    return kept;
}

std::optional<SecantFluidModel::Prediction>
SecantFluidModel::predict(const std::vector<int>& columns, const SolidSolve& solve, Base which,
                          const SolidResponse& respond,
                          const SolidSolveWithResponse& solveAndRespond)
{
    const int k = static_cast<int>(columns.size());
    if (k == 0)
        return std::nullopt;
    const int b = base(which);
    for (int j : columns)
        if (b < 0 || j == b || j < 0 || j >= static_cast<int>(samples_.size()))
            throw std::logic_error("SecantFluidModel: no such sample");
    const auto qr = acceleration::filteredQr(differences(b, columns, false), 0.0,
                                             acceleration::QrFilterKind::Column);
    if (static_cast<int>(qr.kept.size()) != k)
        return std::nullopt; // a zero column
    Prediction p;
    p.columns = k;
    const Eigen::MatrixXd w = differences(b, columns, true);
    // The solid is affine in its loads: for the column W_j = F_r - F_s (r its reference sample),
    // Z_j = S(F_b + W_j) - S(F_b) = S(F_r) - S(F_s). A column whose two samples' answers are kept
    // costs no solve; otherwise S(F_b + W_j) is solved (as the level predictor always did) and
    // the missing answer of the pair kept.
    Sample& origin = samples_[b];
    std::vector<int> references(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j)
        references[j] = reference(columns[j], b);
    const auto answered = [&](int j)
    {
        return samples_[columns[j]].response.size() != 0 &&
               (references[j] == b || samples_[references[j]].response.size() != 0);
    };
    std::vector<int> unknown; // columns whose pair has no answer at this level
    for (int j = 0; j < k; ++j)
        if (!answered(j))
            unknown.push_back(j);
    Eigen::MatrixXd loads(w.rows(), static_cast<Eigen::Index>(unknown.size()));
    for (std::size_t i = 0; i < unknown.size(); ++i)
        loads.col(static_cast<Eigen::Index>(i)) = w.col(unknown[i]);
    const bool respondToUnknown = respond && !unknown.empty();
    std::vector<bool> responded(static_cast<std::size_t>(k), false); // z_j from respond()
    std::optional<Eigen::MatrixXd> withBase; // the columns' answers from the base solve
    if (origin.response.size() == 0)
    {
        if (respondToUnknown && solveAndRespond)
            std::tie(origin.response, withBase.emplace()) = solveAndRespond(origin.force, loads);
        else
            origin.response = solve(origin.force);
        ++p.solidSolves;
    }
    const Eigen::VectorXd response = origin.response;
    Eigen::MatrixXd z(response.size(), k);
    if (respondToUnknown)
    {
        const Eigen::MatrixXd answers = withBase ? *withBase : respond(loads);
        if (answers.rows() != response.size() || answers.cols() != loads.cols())
            throw std::logic_error("SecantFluidModel: the solid response has the wrong size");
        for (std::size_t i = 0; i < unknown.size(); ++i)
        {
            z.col(unknown[i]) = answers.col(static_cast<Eigen::Index>(i));
            responded[unknown[i]] = true;
        }
        p.responseColumns = static_cast<int>(unknown.size());
    }
    for (int j = 0; j < k; ++j)
    {
        if (responded[j])
            continue;
        Sample& s = samples_[columns[j]];
        Sample& r = samples_[references[j]];
        if (answered(j))
        {
            z.col(j) = r.response - s.response;
            continue;
        }
        z.col(j) = solve(origin.force + w.col(j)) - response;
        ++p.solidSolves;
        if (r.response.size() != 0)
            s.response = r.response - z.col(j);
        else if (s.response.size() != 0)
            r.response = s.response + z.col(j);
    }

    // V^+ x = R^{-1} Q^T x.
    const auto pseudoInverse = [&](const Eigen::MatrixXd& x) -> Eigen::MatrixXd
    { return qr.r.triangularView<Eigen::Upper>().solve(qr.q.transpose() * x); };
    const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(k, k) - pseudoInverse(z);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
    p.feedbackMargin = Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues().minCoeff();
    if (!lu.isInvertible())
        return std::nullopt;
    const Eigen::VectorXd c = lu.solve(pseudoInverse(response - samples_[b].u));
    if (!c.allFinite())
        return std::nullopt;
    p.displacement = response + z * c;
    return p;
}

} // namespace fsi::driver
