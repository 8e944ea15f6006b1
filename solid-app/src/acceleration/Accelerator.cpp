// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Accelerator.hpp"

#include "acceleration/Aitken.hpp"
#include "acceleration/ConstantRelaxation.hpp"
#include "acceleration/IqnIls.hpp"
#include "acceleration/NumberText.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::acceleration
{

namespace
{
std::string str(double x)
{
    return std::isnan(x) ? std::string("unset") : numberText(x);
}

void checkInitialRelaxation(double omega, const char* key)
{
    if (!(omega > 0.0 && omega <= 1.0))
        throw std::runtime_error(std::string("acceleration.") + key + " must be in (0, 1] (got " +
                                 str(omega) + "); set it, e.g. 0.5, smaller for strong coupling");
}
} // namespace

void Accelerator::checkStateType(const AcceleratorState& state) const
{
    if (state.type != name())
        throw std::runtime_error("acceleration: restart state was written by '" + state.type +
                                 "' but acceleration.type is '" + name() +
                                 "'; use the same type or start without the accelerator state");
}

void Accelerator::checkSizes(const Eigen::VectorXd& previousIterate,
                             const Eigen::VectorXd& solverOutput, Eigen::Index expected) const
{
    if (previousIterate.size() != solverOutput.size() ||
        (expected >= 0 && previousIterate.size() != expected) || previousIterate.size() == 0)
        throw std::runtime_error("acceleration " + name() + ": interface vector sizes differ (" +
                                 std::to_string(previousIterate.size()) + " sent, " +
                                 std::to_string(solverOutput.size()) + " returned, " +
                                 std::to_string(expected) +
                                 " in this level); the interface must not change within a level");
}

void ConstantParameters::validate() const
{
    if (!(relaxation > 0.0 && relaxation < 2.0))
        throw std::runtime_error("acceleration.relaxation must be in (0, 2) for type constant "
                                 "(got " +
                                 str(relaxation) + "); set it, e.g. 0.5");
}

void AitkenParameters::validate() const
{
    checkInitialRelaxation(initialRelaxation, "initial_relaxation");
    if (initial != "reset" && initial != "carry-over")
        throw std::runtime_error("acceleration.initial '" + initial +
                                 "' is unknown; use reset or carry-over");
    if (!(maxRelaxation > 0.0) || !std::isfinite(maxRelaxation))
        throw std::runtime_error("acceleration.max_relaxation must be > 0 (got " +
                                 str(maxRelaxation) + "); e.g. 1");
    if (!(minRelaxation > 0.0 && minRelaxation <= maxRelaxation))
        throw std::runtime_error("acceleration.min_relaxation must be in (0, max_relaxation] "
                                 "(got " +
                                 str(minRelaxation) + "); e.g. 1e-3");
    if (initialRelaxation > maxRelaxation)
        throw std::runtime_error("acceleration.initial_relaxation " + str(initialRelaxation) +
                                 " exceeds max_relaxation " + str(maxRelaxation) +
                                 "; lower it or raise max_relaxation");
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
                                 str(filterTolerance) + "); e.g. 1e-3");
    if (filter != "qr-column" && filter != "qr-matrix")
        throw std::runtime_error("acceleration.filter '" + filter +
                                 "' is unknown; use qr-column or qr-matrix");
}

void AcceleratorParameters::validate() const
{
    if (type == "constant")
        constant.validate();
    else if (type == "aitken")
        aitken.validate();
    else if (type == "iqn-ils")
        iqnIls.validate();
    else
        throw std::runtime_error("acceleration.type '" + type +
                                 "' is unknown; use one of constant, aitken, iqn-ils");
}

std::unique_ptr<Accelerator> makeAccelerator(const AcceleratorParameters& params)
{
    params.validate();
    if (params.type == "constant")
        return std::make_unique<ConstantRelaxation>(params.constant);
    if (params.type == "aitken")
        return std::make_unique<Aitken>(params.aitken);
    return std::make_unique<IqnIls>(params.iqnIls);
}

ConstantRelaxation::ConstantRelaxation(const ConstantParameters& params) : omega_(params.relaxation)
{
    params.validate();
}

Eigen::VectorXd ConstantRelaxation::update(const Eigen::VectorXd& previousIterate,
                                           const Eigen::VectorXd& solverOutput)
{
    checkSizes(previousIterate, solverOutput, -1);
    return previousIterate + omega_ * (solverOutput - previousIterate);
}

} // namespace fsi::acceleration
