// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fixed-point acceleration of the interface displacement within one time level (after preCICE
// acceleration::Acceleration). Vectors only: no MPI, no FE, no YAML. The driver calls
//   beginLevel(); loop { u = accelerator.update(u, solve(u)); test convergence } endLevel();
// Strategies by keyword (AcceleratorParameters::type), registered in Registry.hpp.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

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

// The parsed coefficients of the chosen strategy, type-erased. A strategy's parameter struct P
// provides (see Aitken.hpp for an example):
//   static constexpr const char* keyword;         // acceleration.type and its coefficient block
//   using Strategy = <the Accelerator class>;     // constructed from P
//   static const std::vector<std::string>& keys(); // the coefficient keys, as documented
//   static P parse(const config::Block& block);   // reads the block (defaults for absent keys)
//   void validate() const;                        // std::runtime_error naming acceleration.<key>
//   std::string echo() const;                     // "{key: value, ...}" for the start-up echo
// and registers itself in Registry.cpp with one line.
class AcceleratorParameters
{
public:
    AcceleratorParameters() = default; // no strategy chosen: validate() and make() throw
    template <class P>
    AcceleratorParameters(const P& params) // NOLINT: implicit by design
        : type_(P::keyword), model_(std::make_shared<Holder<P>>(params))
    {
    }

    const std::string& type() const { return type_; }
    // Throws std::runtime_error, one line naming the key (acceleration.<key>) and the fix.
    void validate() const;
    std::unique_ptr<Accelerator> make() const; // validates first
    std::string echo() const;                  // the coefficients, "{key: value, ...}"

    // The coefficients of strategy P, nullptr when another strategy was chosen. Copies of this
    // object do not share them.
    template <class P> P* get()
    {
        auto* holder = dynamic_cast<Holder<P>*>(model_.get());
        if (!holder)
            return nullptr;
        if (model_.use_count() > 1) // copy on write
        {
            model_ = std::make_shared<Holder<P>>(holder->params);
            holder = static_cast<Holder<P>*>(model_.get());
        }
        return &holder->params;
    }
    template <class P> const P* get() const
    {
        const auto* holder = dynamic_cast<const Holder<P>*>(model_.get());
        return holder ? &holder->params : nullptr;
    }

private:
    struct Model
    {
        virtual ~Model() = default;
        virtual void validate() const = 0;
        virtual std::unique_ptr<Accelerator> make() const = 0;
        virtual std::string echo() const = 0;
    };
    template <class P> struct Holder final : Model
    {
        explicit Holder(const P& p) : params(p) {}
        void validate() const override { params.validate(); }
        std::unique_ptr<Accelerator> make() const override
        {
            return std::make_unique<typename P::Strategy>(params);
        }
        std::string echo() const override { return params.echo(); }
        P params;
    };
    std::string type_;
    std::shared_ptr<Model> model_;
};

// params.make().
std::unique_ptr<Accelerator> makeAccelerator(const AcceleratorParameters& params);

} // namespace fsi::acceleration
