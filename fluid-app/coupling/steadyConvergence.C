// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the stopping rule of one steady solve (see steadyConvergence.H).
#include "steadyConvergence.H"

#include <algorithm>
#include <cmath>

namespace fsi
{
namespace fluid
{

SteadyConvergence::SteadyConvergence(const SolveControls& controls, double residualTolU,
                                     double residualTolP)
    : controls_(controls), residualTolU_(residualTolU), residualTolP_(residualTolP)
{
}

bool SteadyConvergence::update(int iteration, double residualU, double residualP,
                               const double force[3])
{
    if (iteration == 1)
    {
        firstU_ = residualU;
        firstP_ = residualP;
    }
    const bool residualOk = residualsMet(residualU, residualP);
    const bool forceOk = controls_.forceTolerance <= 0 || forceMet(iteration, force);
    stable_ = (residualOk && forceOk) ? stable_ + 1 : 0;
    const bool enoughIterations = iteration >= controls_.minIterations;
    if (stable_ >= controls_.stableIterations && enoughIterations)
        return true;
    inTheMean_ = controls_.bandTolerance > 0 && meanMet(iteration, force) && enoughIterations;
    return inTheMean_;
}

double SteadyConvergence::blockWeight(int iteration, int blockLength)
{
    const int j = (iteration - 1) % blockLength;
    const double s = std::sin(M_PI * (j + 0.5) / blockLength);
    return s * s;
}

void SteadyConvergence::ForceBlock::add(const double force[3], double weight)
{
    for (int i = 0; i < 3; ++i)
    {
        weightedSum[i] += weight * force[i];
        low[i] = count == 0 ? force[i] : std::min(low[i], force[i]);
        high[i] = count == 0 ? force[i] : std::max(high[i], force[i]);
    }
    ++count;
}

bool SteadyConvergence::meanMet(int iteration, const double force[3])
{
    const int n = controls_.bandWindow;
    current_.add(force, blockWeight(iteration, n));
    if (current_.count < n)
        return false;
    bool met = false;
    if (previous_.count == n)
    {
        double mean2 = 0, change2 = 0, band2 = 0;
        for (int i = 0; i < 3; ++i)
        {
            // each block's weights sum to n / 2
            const double mean = (previous_.weightedSum[i] + current_.weightedSum[i]) / n;
            const double change = 2 * (current_.weightedSum[i] - previous_.weightedSum[i]) / n;
            const double half = 0.5 * (std::max(previous_.high[i], current_.high[i]) -
                                       std::min(previous_.low[i], current_.low[i]));
            mean2 += mean * mean;
            change2 += change * change;
            band2 += half * half;
        }
        const double scale = std::max(std::sqrt(mean2), controls_.bandReferenceForce);
        band_ = scale > 0 ? std::sqrt(band2) / scale : HUGE_VAL;
        meanChange_ = scale > 0 ? std::sqrt(change2) / scale : HUGE_VAL;
        met = band_ <= controls_.bandTolerance &&
              meanChange_ <= std::max(controls_.forceTolerance, controls_.bandMeanTolerance);
    }
    previous_ = current_;
    current_ = ForceBlock();
    return met;
}

double SteadyConvergence::estimatedForceError(const std::vector<double>& changes)
{
    const std::size_t m = changes.size();
    double rho = 0.9;
    if (m >= 4 && changes[m - 4] > 1e-300)
        rho = std::pow(changes[m - 1] / changes[m - 4], 1.0 / 3.0);
    rho = std::min(std::max(rho, 0.0), 0.98);
    return changes[m - 1] * rho / (1 - rho);
}

double SteadyConvergence::oscillationBand(const std::vector<double>& forces)
{
    const std::size_t m = forces.size() / 3;
    double band2 = 0;
    for (std::size_t i = 0; i < 3 && m >= 3; ++i)
    {
        bool reverses = false;
        double low = forces[i], high = forces[i], previousChange = 0;
        for (std::size_t k = 1; k < m; ++k)
        {
            const double value = forces[3 * k + i];
            const double change = value - forces[3 * (k - 1) + i];
            reverses = reverses || change * previousChange < 0;
            if (change != 0)
                previousChange = change;
            low = std::min(low, value);
            high = std::max(high, value);
        }
        if (reverses)
            band2 += 0.25 * (high - low) * (high - low);
    }
    return std::sqrt(band2);
}

bool SteadyConvergence::residualsMet(double residualU, double residualP) const
{
    if (!controls_.residualRequired)
        return true;
    const bool dropOk = controls_.residualDrop > 0 &&
                        residualU <= controls_.residualDrop * firstU_ &&
                        residualP <= controls_.residualDrop * firstP_;
    const bool absoluteOk = residualU <= residualTolU_ && residualP <= residualTolP_;
    return dropOk || absoluteOk;
}

bool SteadyConvergence::forceMet(int iteration, const double force[3])
{
    const double change = std::sqrt(std::pow(force[0] - previousForce_[0], 2) +
                                    std::pow(force[1] - previousForce_[1], 2) +
                                    std::pow(force[2] - previousForce_[2], 2));
    std::copy(force, force + 3, previousForce_);
    if (iteration == 1)
        return false;
    forceChanges_.push_back(change);
    double error = controls_.estimateError ? estimatedForceError(forceChanges_) : change;
    if (controls_.estimateError && controls_.oscillationWindow > 0)
    {
        const std::size_t keep = 3 * static_cast<std::size_t>(controls_.oscillationWindow + 1);
        recentForces_.insert(recentForces_.end(), force, force + 3);
        if (recentForces_.size() > keep)
            recentForces_.erase(recentForces_.begin(),
                                recentForces_.begin() +
                                    static_cast<std::ptrdiff_t>(recentForces_.size() - keep));
        error = std::max(error, oscillationBand(recentForces_));
    }
    const double magF = std::sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]);
    return error <= controls_.forceTolerance * magF;
}

} // namespace fluid
} // namespace fsi
