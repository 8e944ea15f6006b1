// SPDX-License-Identifier: GPL-3.0-or-later
//
// Convergence test of the coupling iteration (the iteration cap is the driver's).
// With r = u_hat_i - u_{i-1} of length n:
//   absolute (the paper): |r| / sqrt(n) < absolute_tolerance      [unit of u, m]
//   relative:             |r| < relative_tolerance |u_hat_i|
// A criterion is active when its tolerance is > 0; converged when every active one holds.
#pragma once

#include <Eigen/Core>

#include <string>

namespace fsi::acceleration
{

struct ConvergenceParameters
{
    double absoluteTolerance = 0.0; // epsilon of the paper [m]; 0 = off
    double relativeTolerance = 0.0; // 0 = off
    void validate() const;          // throws unless at least one is > 0, none negative
};

struct ConvergenceMeasure
{
    double rmsResidual = 0.0;      // |r| / sqrt(n)
    double relativeResidual = 0.0; // |r| / |u_hat| (inf when u_hat = 0 and r != 0)
    bool converged = false;
    bool finite = true;           // false when r has NaN/inf: the driver stops the level
    std::string toString() const; // "|r|/sqrt(n) 1.2e-07 |r|/|u| 3.4e-05 converged"
};

// Pre: vectors of the same non-zero length.
ConvergenceMeasure measureConvergence(const Eigen::VectorXd& previousIterate,
                                      const Eigen::VectorXd& solverOutput,
                                      const ConvergenceParameters& params);

} // namespace fsi::acceleration
