// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Convergence.hpp"

#include "config/YamlReader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace fsi::acceleration
{

void ConvergenceParameters::validate() const
{
    if (!(absoluteTolerance >= 0.0) || !(relativeTolerance >= 0.0))
        throw std::runtime_error(
            "coupling convergence tolerances must be >= 0 (absolute_tolerance " +
            config::formatNumber(absoluteTolerance) + ", relative_tolerance " +
            config::formatNumber(relativeTolerance) + ")");
    if (!(absoluteTolerance > 0.0) && !(relativeTolerance > 0.0))
        throw std::runtime_error("coupling convergence needs absolute_tolerance (|r|/sqrt(n) in m, "
                                 "e.g. 1e-8) or relative_tolerance (e.g. 1e-5) > 0");
    if (!(bandFactor >= 0.0) || !std::isfinite(bandFactor))
        throw std::runtime_error("coupling convergence band_factor must be >= 0 (got " +
                                 config::formatNumber(bandFactor) +
                                 "; 2 = the band's full width, 0 = off)");
}

ConvergenceParameters ConvergenceParameters::widenedForBand(double band, double rmsOutput) const
{
    ConvergenceParameters widened = *this;
    if (!(band > 0.0) || !(bandFactor > 0.0))
        return widened;
    if (absoluteTolerance > 0.0)
        widened.absoluteTolerance = std::max(absoluteTolerance, bandFactor * band * rmsOutput);
    if (relativeTolerance > 0.0)
        widened.relativeTolerance = std::max(relativeTolerance, bandFactor * band);
    return widened;
}

std::string ConvergenceParameters::describe() const
{
    std::string text;
    if (absoluteTolerance > 0.0)
        text = "|r|/sqrt(n) < " + config::formatNumber(absoluteTolerance) + " m";
    if (relativeTolerance > 0.0)
        text += (text.empty() ? "" : ", ") + std::string("|r|/|u| < ") +
                config::formatNumber(relativeTolerance);
    return text;
}

std::string ConvergenceMeasure::toString() const
{
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, "|r|/sqrt(n) %.3e |r|/|u| %.3e %s", rmsResidual,
                  relativeResidual,
                  !finite ? "NOT FINITE" : (converged ? "converged" : "not converged"));
    return buffer;
}

ConvergenceMeasure measureConvergence(const Eigen::VectorXd& previousIterate,
                                      const Eigen::VectorXd& solverOutput,
                                      const ConvergenceParameters& params)
{
    ConvergenceMeasure m;
    const double n = static_cast<double>(previousIterate.size());
    const double residualNorm = (solverOutput - previousIterate).norm();
    const double outputNorm = solverOutput.norm();
    m.rmsResidual = residualNorm / std::sqrt(n);
    m.relativeResidual = outputNorm > 0.0     ? residualNorm / outputNorm
                         : residualNorm > 0.0 ? std::numeric_limits<double>::infinity()
                                              : 0.0;
    m.finite = std::isfinite(residualNorm) && std::isfinite(outputNorm);
    m.converged = m.finite;
    if (params.absoluteTolerance > 0.0)
        m.converged = m.converged && m.rmsResidual < params.absoluteTolerance;
    if (params.relativeTolerance > 0.0)
        m.converged = m.converged && m.relativeResidual < params.relativeTolerance;
    return m;
}

} // namespace fsi::acceleration
