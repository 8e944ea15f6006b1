// SPDX-License-Identifier: GPL-3.0-or-later
// constant: u_i = u_{i-1} + omega (u_hat_i - u_{i-1}), omega fixed.
#pragma once

#include "acceleration/Accelerator.hpp"

namespace fsi::acceleration
{

class ConstantRelaxation;

// constant: u_i = u_{i-1} + omega r_i. Block `constant: {relaxation: 0.3}`.
struct ConstantParameters
{
    static constexpr const char* keyword = "constant";
    using Strategy = ConstantRelaxation;
    double relaxation = std::numeric_limits<double>::quiet_NaN(); // omega, required, (0, 2)

    static const std::vector<std::string>& keys();
    static ConstantParameters parse(const config::Block& layer); // reads layer.<keyword> (required)
    void validate() const;
    std::string echo() const;
};

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
