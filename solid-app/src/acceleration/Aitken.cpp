// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Aitken.hpp"

#include "acceleration/ParameterChecks.hpp"
#include "config/YamlReader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace fsi::acceleration
{

const std::vector<std::string>& AitkenParameters::keys()
{
    static const std::vector<std::string> k{"initial_relaxation", "initial", "max_relaxation",
                                            "min_relaxation", "negative_factor"};
    return k;
}

AitkenParameters AitkenParameters::parse(const config::Block& layer)
{
    const config::Block b = layer.block(keyword);
    b.allowOnly(keys());
    AitkenParameters p;
    p.initialRelaxation = b.number("initial_relaxation");
    p.initial = b.choice("initial", {"reset", "carry-over"}, "reset");
    p.maxRelaxation = b.number("max_relaxation", p.maxRelaxation);
    p.minRelaxation = b.number("min_relaxation", p.minRelaxation);
    p.negativeFactor = b.choice("negative_factor", {"restart", "keep"}, p.negativeFactor);
    return p;
}

void AitkenParameters::validate() const
{
    checkInitialRelaxation(initialRelaxation, "initial_relaxation");
    if (initial != "reset" && initial != "carry-over")
        throw std::runtime_error("acceleration.initial '" + initial +
                                 "' is unknown; use reset or carry-over");
    if (negativeFactor != "restart" && negativeFactor != "keep")
        throw std::runtime_error("acceleration.negative_factor '" + negativeFactor +
                                 "' is unknown; use restart or keep");
    if (!(maxRelaxation > 0.0) || !std::isfinite(maxRelaxation))
        throw std::runtime_error("acceleration.max_relaxation must be > 0 (got " +
                                 valueText(maxRelaxation) + "); e.g. 1");
    if (!(minRelaxation > 0.0 && minRelaxation <= maxRelaxation))
        throw std::runtime_error("acceleration.min_relaxation must be in (0, max_relaxation] "
                                 "(got " +
                                 valueText(minRelaxation) + "); e.g. 1e-3");
    if (initialRelaxation > maxRelaxation)
        throw std::runtime_error("acceleration.initial_relaxation " + valueText(initialRelaxation) +
                                 " exceeds max_relaxation " + valueText(maxRelaxation) +
                                 "; lower it or raise max_relaxation");
}

std::string AitkenParameters::echo() const
{
    std::ostringstream s;
    s << "{initial_relaxation: " << initialRelaxation << ", initial: " << initial
      << ", max_relaxation: " << maxRelaxation << ", min_relaxation: " << minRelaxation
      << ", negative_factor: " << negativeFactor << "}";
    return s.str();
}

Aitken::Aitken(const AitkenParameters& params)
    : params_(params), carryOver_(params.initial == "carry-over"),
      restartOnNegative_(params.negativeFactor == "restart")
{
    params_.validate();
}

void Aitken::beginLevel()
{
    iteration_ = 0;
    note_.clear();
}

void Aitken::scaleRelaxation(double factor)
{
    params_.initialRelaxation *= factor;
    params_.maxRelaxation = std::max(params_.minRelaxation, params_.maxRelaxation * factor);
}

double Aitken::clamp(double omega, const char* what)
{
    const double magnitude = std::fabs(omega);
    double clamped = omega;
    if (magnitude > params_.maxRelaxation)
        clamped = std::copysign(params_.maxRelaxation, omega);
    else if (magnitude < params_.minRelaxation)
        clamped = std::copysign(params_.minRelaxation, omega);
    if (clamped != omega)
    {
        char buffer[200];
        std::snprintf(buffer, sizeof buffer,
                      "aitken: %s omega %.4g clamped to %.4g (min_relaxation %.4g, "
                      "max_relaxation %.4g)",
                      what, omega, clamped, params_.minRelaxation, params_.maxRelaxation);
        note_ = buffer;
    }
    return clamped;
}

double Aitken::restart(double factor)
{
    note_ = "aitken: new omega " + config::formatNumber(factor) +
            " <= 0 (no contraction along the last residual), restarted at initial_relaxation " +
            config::formatNumber(params_.initialRelaxation);
    return params_.initialRelaxation;
}

Eigen::VectorXd Aitken::update(const Eigen::VectorXd& previousIterate,
                               const Eigen::VectorXd& solverOutput)
{
    note_.clear();
    checkSizes(previousIterate, solverOutput, iteration_ > 0 ? previousResidual_.size() : -1);
    Eigen::VectorXd residual = solverOutput - previousIterate;
    if (iteration_ == 0)
    {
        if (carryOver_ && !std::isnan(levelOmega_))
        {
            // The carried factor is kept in [min_relaxation, max_relaxation] (positive).
            omega_ = std::min(std::max(levelOmega_, params_.minRelaxation), params_.maxRelaxation);
            if (omega_ != levelOmega_)
                note_ = "aitken: carried-over omega " + config::formatNumber(levelOmega_) +
                        " clamped to " + config::formatNumber(omega_) + " (min_relaxation " +
                        config::formatNumber(params_.minRelaxation) + ", max_relaxation " +
                        config::formatNumber(params_.maxRelaxation) + ")";
        }
        else
            omega_ = params_.initialRelaxation;
    }
    else
    {
        const Eigen::VectorXd change = residual - previousResidual_;
        const double denominator = change.squaredNorm();
        if (denominator > 0.0 && std::isfinite(denominator))
        {
            const double factor = -omega_ * previousResidual_.dot(change) / denominator;
            if (factor <= 0.0 && restartOnNegative_)
                omega_ = restart(factor);
            else
                omega_ = clamp(factor, "new");
        }
        else
            note_ = "aitken: residual unchanged, omega kept at " + config::formatNumber(omega_);
    }
    ++iteration_;
    previousResidual_ = std::move(residual);
    return previousIterate + omega_ * previousResidual_;
}

void Aitken::endLevel()
{
    levelOmega_ = omega_;
}

AcceleratorState Aitken::saveState() const
{
    return {name(), {1}, {levelOmega_}};
}

void Aitken::loadState(const AcceleratorState& state)
{
    checkStateType(state);
    if (state.values.size() != 1)
        throw std::runtime_error("acceleration: aitken restart state must hold 1 value, has " +
                                 std::to_string(state.values.size()) +
                                 "; the restart file is damaged or from another version");
    levelOmega_ = state.values[0];
}

} // namespace fsi::acceleration
