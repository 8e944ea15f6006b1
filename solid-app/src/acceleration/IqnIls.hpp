// SPDX-License-Identifier: GPL-3.0-or-later
//
// iqn-ils: interface quasi-Newton with an approximation of the inverse Jacobian from a
// least-squares model (Degroote, Bathe, Vierendeels 2009; preCICE's IQN-ILS). On the secant
// columns of QuasiNewton.hpp:
//   c = argmin |V c + r_i|   (filtered QR of V),   u_i = u_hat_i + W c.
// On a linear problem of size n without reuse, the (n+1)-th update returns the fixed point.
#pragma once

#include "acceleration/QuasiNewton.hpp"

namespace fsi::acceleration
{

class IqnIls;

// Block `iqn-ils: {initial_relaxation: 0.3, max_columns: 100, reuse_levels: 8, filter:
// qr-column, filter_tolerance: 1e-3}` (the quasi-Newton keys, nothing of its own).
struct IqnIlsParameters : QuasiNewtonParameters
{
    static constexpr const char* keyword = "iqn-ils";
    using Strategy = IqnIls;
    static const std::vector<std::string>& keys() { return commonKeys(); }
    static IqnIlsParameters parse(const config::Block& layer); // reads layer.<keyword> (required)
    std::string echo() const { return "{" + echoCommon() + "}"; }
};

class IqnIls final : public QuasiNewton
{
public:
    explicit IqnIls(const IqnIlsParameters& params);
    std::string name() const override { return "iqn-ils"; }

private:
    Eigen::VectorXd step(const FilteredQr& qr, const Eigen::MatrixXd& w,
                         const Eigen::VectorXd& residual,
                         const Eigen::VectorXd& solverOutput) override;
};

} // namespace fsi::acceleration
