// SPDX-License-Identifier: GPL-3.0-or-later
//
// Convergence test of the coupling iteration (the iteration cap is the driver's).
// With r = u_hat_i - u_{i-1} of length n:
//   absolute (the paper): |r| / sqrt(n) < absolute_tolerance      [unit of u, m]
//   relative:             |r| < relative_tolerance |u_hat_i|
// A criterion is active when its tolerance is > 0; converged when every active one holds.
// A flow without a steady state, accepted in the mean with a relative force band b (the fluid's
// +-b around its mean), answers the same interface only to about the band's full width from one
// start to the next, so the output u_hat is known only to about 2 b |u_hat|: for such an
// iteration the tolerances are widened to band_factor * b (relative) and
// band_factor * b * |u_hat| / sqrt(n) (absolute), never tightened.
#pragma once

#include <Eigen/Core>

#include <string>

namespace fsi::acceleration
{

struct ConvergenceParameters
{
    double absoluteTolerance = 0.0; // epsilon of the paper [m]; 0 = off
    double relativeTolerance = 0.0; // 0 = off
    // Widening for a flow accepted in the mean (see above); 0 = off (the tolerances stand).
    double bandFactor = 2.0;
    void validate() const; // throws unless at least one tolerance is > 0, none negative
    // The tolerances for an output whose flow was accepted in the mean with relative band
    // `band` (0: a steady flow, returns *this) and rms(u_hat) = rmsOutput [m].
    ConvergenceParameters widenedForBand(double band, double rmsOutput) const;
    // The active criteria, e.g. "|r|/sqrt(n) < 5e-06 m, |r|/|u| < 0.001"
    std::string describe() const;
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
