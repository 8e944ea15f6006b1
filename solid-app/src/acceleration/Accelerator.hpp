// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fixed-point acceleration of the interface displacement within one time level (after preCICE
// acceleration::Acceleration). Vectors only: no MPI, no FE, no YAML. The driver calls
//   beginLevel(); loop { u = accelerator.update(u, solve(u)); test convergence } endLevel();
// Strategies by keyword (AcceleratorParameters::type), registered in Registry.hpp.
#pragma once

#include "config/Strategy.hpp"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fsi::acceleration
{

// What a strategy carries between levels, for restart. Plain data, written by the io layer.
struct AcceleratorState
{
    std::string type;        // keyword of the strategy that wrote it
    std::vector<long> sizes; // strategy-specific layout (see each strategy)
    std::vector<double> values;
};

class Accelerator
{
public:
    static constexpr const char* kConfigKey = "acceleration"; // for config::Strategy messages
    virtual ~Accelerator() = default;

    virtual std::string name() const = 0;

    // Start of a time level. Keeps what the strategy carries over between levels (Aitken omega,
    // IQN-ILS columns of converged levels); drops the iteration data of an unfinished level.
    virtual void beginLevel() = 0;

    // Given the previous iterate u_{i-1} (what was sent to the solvers) and the solver output
    // u_hat_i, return the next iterate u_i. Residual r_i = u_hat_i - u_{i-1}.
    // Pre: beginLevel() called; both vectors of the same length n, fixed within a level (and
    // across levels for IQN-ILS reuse). Unit: whatever the driver uses (m), consistently.
    virtual Eigen::VectorXd update(const Eigen::VectorXd& previousIterate,
                                   const Eigen::VectorXd& solverOutput) = 0;

    // The level has converged: commit the data reused by later levels.
    virtual void endLevel() = 0;

    // Relaxation factor used by the last update (for the log); NaN when not meaningful
    // (a quasi-Newton step).
    virtual double lastRelaxation() const { return std::numeric_limits<double>::quiet_NaN(); }

    // Stronger relaxation for a redone level (a recovery cure): multiplies the strategy's
    // relaxation factors (omega, omega_0, the Aitken upper clamp) by factor in (0, 1].
    // Takes effect from the next beginLevel(); keeps what the strategy carries over.
    virtual void scaleRelaxation(double factor) = 0;

    // What the last update did that the log should say (a clamp, filtered columns, a fallback);
    // empty when nothing noteworthy. The library never prints.
    const std::string& lastNote() const { return note_; }

    // Restart: state after endLevel() (between levels). loadState throws std::runtime_error
    // when the state was written by another type or does not fit.
    virtual AcceleratorState saveState() const { return {name(), {}, {}}; }
    virtual void loadState(const AcceleratorState& state) { checkStateType(state); }

protected:
    void checkStateType(const AcceleratorState& state) const;
    // Throws when the two vectors differ in length or expected (>= 0) is not their length.
    void checkSizes(const Eigen::VectorXd& previousIterate, const Eigen::VectorXd& solverOutput,
                    Eigen::Index expected) const;
    std::string note_;
};

// The chosen strategy with its parsed coefficients (config/Strategy.hpp says what a strategy's
// parameter struct provides; Registry.hpp lists them).
using AcceleratorParameters = config::Strategy<Accelerator>;

// params.make().
std::unique_ptr<Accelerator> makeAccelerator(const AcceleratorParameters& params);

} // namespace fsi::acceleration
