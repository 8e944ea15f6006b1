// SPDX-License-Identifier: GPL-3.0-or-later
//
// iqn-ils: interface quasi-Newton with an approximation of the inverse Jacobian from a
// least-squares model (Degroote, Bathe, Vierendeels 2009; preCICE's IQN-ILS).
// With r_i = u_hat_i - u_{i-1}: V = [r_i - r_{i-1}, ...], W = [u_hat_i - u_hat_{i-1}, ...]
// (newest first: this level, then the last reuse_levels converged levels, at most max_columns),
//   c = argmin |V c + r_i|   (filtered QR of V, see QrFilter.hpp),   u_i = u_hat_i + W c.
// The first update of every level uses constant relaxation u_i = u_{i-1} + omega_0 r_i, as does
// any update whose V is empty or filtered away (told in lastNote()).
// On a linear problem of size n without reuse, the (n+1)-th update returns the fixed point.
// Restart state: sizes = {n, L, m_1..m_L} (L stored levels, m_l columns), values = for each
// level V then W, column-major.
#pragma once

#include "acceleration/Accelerator.hpp"
#include "acceleration/QrFilter.hpp"

#include <deque>

namespace fsi::acceleration
{

class IqnIls final : public Accelerator
{
public:
    explicit IqnIls(const IqnIlsParameters& params);
    std::string name() const override { return "iqn-ils"; }
    void beginLevel() override;
    Eigen::VectorXd update(const Eigen::VectorXd& previousIterate,
                           const Eigen::VectorXd& solverOutput) override;
    void endLevel() override;
    double lastRelaxation() const override { return omega_; }
    // omega_0 of the first update of each level times factor.
    void scaleRelaxation(double factor) override { params_.initialRelaxation *= factor; }
    AcceleratorState saveState() const override;
    void loadState(const AcceleratorState& state) override;

    // Columns used by the last update (after the cap, before the filter) and those kept.
    int lastColumns() const { return lastColumns_; }
    int lastKeptColumns() const { return lastKept_; }

private:
    struct Columns
    {
        Eigen::MatrixXd v, w; // n x m, newest first
    };
    IqnIlsParameters params_;
    QrFilterKind filterKind_;
    std::deque<Eigen::VectorXd> currentV_, currentW_; // this level, newest first
    std::deque<Columns> past_;                        // converged levels, newest first
    Eigen::VectorXd previousResidual_, previousOutput_;
    int iteration_ = 0;
    double omega_ = std::numeric_limits<double>::quiet_NaN();
    int lastColumns_ = 0, lastKept_ = 0;
};

} // namespace fsi::acceleration
