// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/QuasiNewton.hpp"

#include "acceleration/ParameterChecks.hpp"
#include "config/YamlReader.hpp"

#include <sstream>

#include <stdexcept>

namespace fsi::acceleration
{

const std::vector<std::string>& QuasiNewtonParameters::commonKeys()
{
    static const std::vector<std::string> k{
        "initial_relaxation", "max_columns",  "reuse_levels",    "filter",
        "filter_tolerance",   "first_update", "reused_on_growth"};
    return k;
}

void QuasiNewtonParameters::parseCommon(const config::Block& b)
{
    initialRelaxation = b.number("initial_relaxation");
    maxColumns = b.integer("max_columns", maxColumns);
    reuseLevels = b.integer("reuse_levels", reuseLevels);
    filter = b.choice("filter", {"qr-column", "qr-matrix"}, filter);
    filterTolerance = b.number("filter_tolerance", filterTolerance);
    firstUpdate = b.choice("first_update", {"relaxation", "quasi-newton"}, firstUpdate);
    reusedOnGrowth = b.choice("reused_on_growth", {"keep", "drop"}, reusedOnGrowth);
}

std::string QuasiNewtonParameters::echoCommon() const
{
    std::ostringstream s;
    s << "initial_relaxation: " << initialRelaxation << ", max_columns: " << maxColumns
      << ", reuse_levels: " << reuseLevels << ", filter: " << filter
      << ", filter_tolerance: " << filterTolerance << ", first_update: " << firstUpdate
      << ", reused_on_growth: " << reusedOnGrowth;
    return s.str();
}

void QuasiNewtonParameters::validate() const
{
    checkInitialRelaxation(initialRelaxation, "initial_relaxation");
    if (maxColumns < 1)
        throw std::runtime_error("acceleration.max_columns must be >= 1 (got " +
                                 std::to_string(maxColumns) + "); e.g. 100");
    if (reuseLevels < 0)
        throw std::runtime_error("acceleration.reuse_levels must be >= 0 (got " +
                                 std::to_string(reuseLevels) + "); 0 switches reuse off");
    if (!(filterTolerance >= 0.0 && filterTolerance < 1.0))
        throw std::runtime_error("acceleration.filter_tolerance must be in [0, 1) (got " +
                                 valueText(filterTolerance) + "); e.g. 1e-3");
    if (filter != "qr-column" && filter != "qr-matrix")
        throw std::runtime_error("acceleration.filter '" + filter +
                                 "' is unknown; use qr-column or qr-matrix");
    if (firstUpdate != "relaxation" && firstUpdate != "quasi-newton")
        throw std::runtime_error("acceleration.first_update '" + firstUpdate +
                                 "' is unknown; use relaxation or quasi-newton");
    if (reusedOnGrowth != "keep" && reusedOnGrowth != "drop")
        throw std::runtime_error("acceleration.reused_on_growth '" + reusedOnGrowth +
                                 "' is unknown; use keep or drop");
}

QuasiNewton::QuasiNewton(const QuasiNewtonParameters& params)
    : params_(params),
      filterKind_(params.filter == "qr-matrix" ? QrFilterKind::Matrix : QrFilterKind::Column)
{
    params_.validate();
}

void QuasiNewton::beginLevel()
{
    currentV_.clear();
    currentW_.clear();
    iteration_ = 0;
    reusedDropped_ = false;
    note_.clear();
}

Eigen::VectorXd QuasiNewton::update(const Eigen::VectorXd& previousIterate,
                                    const Eigen::VectorXd& solverOutput)
{
    note_.clear();
    checkSizes(previousIterate, solverOutput, iteration_ > 0 ? previousResidual_.size() : -1);
    const Eigen::Index n = previousIterate.size();
    if (!past_.empty() && past_.front().v.rows() != n)
        throw std::runtime_error("acceleration " + name() + ": interface size changed from " +
                                 std::to_string(past_.front().v.rows()) + " to " +
                                 std::to_string(n) + "; reuse_levels needs a fixed interface");
    Eigen::VectorXd residual = solverOutput - previousIterate;
    if (iteration_ > 0 && !reusedDropped_ && !past_.empty() && params_.reusedOnGrowth == "drop" &&
        residual.norm() > previousResidual_.norm())
    {
        reusedDropped_ = true;
        note_ = name() + ": residual grew, reused columns dropped for this level";
    }
    if (iteration_ > 0)
    {
        currentV_.push_front(residual - previousResidual_);
        currentW_.push_front(solverOutput - previousOutput_);
        while (static_cast<int>(currentV_.size()) > params_.maxColumns)
        {
            currentV_.pop_back();
            currentW_.pop_back();
        }
    }
    const bool relaxFirst = iteration_ == 0 && params_.firstUpdate == "relaxation";
    ++iteration_;
    previousOutput_ = solverOutput;
    previousResidual_ = residual;

    // Columns: this level newest first, then the reused levels, capped at max_columns.
    Eigen::Index m = static_cast<Eigen::Index>(currentV_.size());
    if (!reusedDropped_)
        for (const Columns& level : past_)
            m += level.v.cols();
    m = std::min<Eigen::Index>(m, params_.maxColumns);
    lastColumns_ = relaxFirst ? 0 : static_cast<int>(m);
    lastKept_ = 0;
    if (relaxFirst || m == 0)
    {
        omega_ = params_.initialRelaxation;
        return previousIterate + omega_ * residual;
    }
    Eigen::MatrixXd v(n, m), w(n, m);
    assembleColumns(m, v, w);

    const FilteredQr qr = filteredQr(v, params_.filterTolerance, filterKind_);
    lastKept_ = static_cast<int>(qr.kept.size());
    if (!qr.dropped.empty())
        note_ += (note_.empty() ? "" : "; ") + name() + ": qr filter dropped " +
                 std::to_string(qr.dropped.size()) + " of " + std::to_string(m) + " columns";
    if (qr.kept.empty())
    {
        omega_ = params_.initialRelaxation;
        note_ +=
            (note_.empty() ? "" : "; ") + name() + ": no usable columns, constant relaxation step";
        return previousIterate + omega_ * residual;
    }
    omega_ = std::numeric_limits<double>::quiet_NaN();
    return step(qr, w, residual, solverOutput);
}

void QuasiNewton::assembleColumns(Eigen::Index m, Eigen::MatrixXd& v, Eigen::MatrixXd& w) const
{
    Eigen::Index j = 0;
    for (size_t i = 0; i < currentV_.size() && j < m; ++i, ++j)
    {
        v.col(j) = currentV_[i];
        w.col(j) = currentW_[i];
    }
    for (const Columns& level : past_)
        for (Eigen::Index i = 0; i < level.v.cols() && j < m && !reusedDropped_; ++i, ++j)
        {
            v.col(j) = level.v.col(i);
            w.col(j) = level.w.col(i);
        }
}

void QuasiNewton::endLevel()
{
    if (params_.reuseLevels > 0 && !currentV_.empty())
    {
        const Eigen::Index n = currentV_.front().size();
        const Eigen::Index m = static_cast<Eigen::Index>(currentV_.size());
        Columns level{Eigen::MatrixXd(n, m), Eigen::MatrixXd(n, m)};
        for (Eigen::Index i = 0; i < m; ++i)
        {
            level.v.col(i) = currentV_[static_cast<size_t>(i)];
            level.w.col(i) = currentW_[static_cast<size_t>(i)];
        }
        past_.push_front(std::move(level));
        while (static_cast<int>(past_.size()) > params_.reuseLevels)
            past_.pop_back();
    }
    currentV_.clear();
    currentW_.clear();
}

AcceleratorState QuasiNewton::saveState() const
{
    AcceleratorState state{name(), {}, {}};
    const long n = past_.empty() ? 0 : static_cast<long>(past_.front().v.rows());
    state.sizes = {n, static_cast<long>(past_.size())};
    for (const Columns& level : past_)
    {
        state.sizes.push_back(static_cast<long>(level.v.cols()));
        state.values.insert(state.values.end(), level.v.data(), level.v.data() + level.v.size());
        state.values.insert(state.values.end(), level.w.data(), level.w.data() + level.w.size());
    }
    return state;
}

void QuasiNewton::loadState(const AcceleratorState& state)
{
    checkStateType(state);
    const auto damaged = [this](const std::string& what)
    {
        return std::runtime_error("acceleration: " + name() + " restart state " + what +
                                  "; the restart file is damaged or from another version");
    };
    if (state.sizes.size() < 2 || state.sizes[0] < 0 || state.sizes[1] < 0 ||
        state.sizes.size() != 2 + static_cast<size_t>(state.sizes[1]))
        throw damaged("has an inconsistent size table");
    const Eigen::Index n = state.sizes[0];
    size_t expected = 0;
    for (size_t l = 2; l < state.sizes.size(); ++l)
    {
        if (state.sizes[l] < 0)
            throw damaged("has a negative column count");
        expected += 2 * static_cast<size_t>(n) * static_cast<size_t>(state.sizes[l]);
    }
    if (expected != state.values.size())
        throw damaged("holds " + std::to_string(state.values.size()) + " values, expected " +
                      std::to_string(expected));
    past_.clear();
    const double* data = state.values.data();
    for (size_t l = 2; l < state.sizes.size(); ++l)
    {
        const Eigen::Index m = state.sizes[l];
        Columns level{Eigen::Map<const Eigen::MatrixXd>(data, n, m),
                      Eigen::Map<const Eigen::MatrixXd>(data + n * m, n, m)};
        data += 2 * n * m;
        past_.push_back(std::move(level));
    }
    while (static_cast<int>(past_.size()) > params_.reuseLevels)
        past_.pop_back();
}

} // namespace fsi::acceleration
