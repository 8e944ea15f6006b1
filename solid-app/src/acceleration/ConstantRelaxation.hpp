// SPDX-License-Identifier: GPL-3.0-or-later
// constant: u_i = u_{i-1} + omega (u_hat_i - u_{i-1}), omega fixed.
#pragma once

#include "acceleration/Accelerator.hpp"

namespace fsi::acceleration
{

class ConstantRelaxation final : public Accelerator
{
public:
    explicit ConstantRelaxation(const ConstantParameters& params);
    std::string name() const override { return "constant"; }
    void beginLevel() override { note_.clear(); }
    Eigen::VectorXd update(const Eigen::VectorXd& previousIterate,
                           const Eigen::VectorXd& solverOutput) override;
    void endLevel() override {}
    double lastRelaxation() const override { return omega_; }
    void scaleRelaxation(double factor) override { omega_ *= factor; }

private:
    double omega_;
};

} // namespace fsi::acceleration
