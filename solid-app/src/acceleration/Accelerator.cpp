// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Accelerator.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::acceleration
{

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

std::unique_ptr<Accelerator> makeAccelerator(const AcceleratorParameters& params)
{
    return params.make();
}

} // namespace fsi::acceleration
