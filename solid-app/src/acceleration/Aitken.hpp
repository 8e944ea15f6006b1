// SPDX-License-Identifier: GPL-3.0-or-later
//
// aitken: dynamic relaxation by Aitken's delta^2 method, the paper's eq. 10. With the residual
// of this update r_new = u_hat_i - u_{i-1}, the previous one r_prev and the previous factor
// omega_prev (paper: r_{i+1}, r_i, omega_{i-1}):
//   omega = -omega_prev r_prev^T (r_new - r_prev) / |r_new - r_prev|^2,  u_i = u_{i-1} + omega
//   r_new
// First update of a level: "reset" uses omega_0; "carry-over" uses the last omega of the
// previous converged level clamped to [min_relaxation, max_relaxation] (omega_0 on the first
// level). A factor <= 0 says the last residual change was not a contraction along r_prev (with a
// non-normal interface Jacobian, e.g. twist driving bending, this happens although every
// eigenvalue is < 1, and signed steps then cycle without converging): negative_factor "restart"
// (default) restarts from omega_0; "keep" keeps the sign (the literal eq. 10, for a locally
// expanding map). Every omega is then clamped to min_relaxation <= |omega| <= max_relaxation.
// If r_new == r_prev (no information) omega_prev is kept. Each of these is told in lastNote().
// Restart state: values = {last omega of the last converged level} (NaN before the first).
#pragma once

#include "acceleration/Accelerator.hpp"

namespace fsi::acceleration
{

class Aitken;

// Block `aitken: {initial_relaxation: 0.5, initial: reset, max_relaxation: 1, min_relaxation:
// 1e-3, negative_factor: restart}`.
struct AitkenParameters
{
    static constexpr const char* keyword = "aitken";
    using Strategy = Aitken;
    double initialRelaxation = std::numeric_limits<double>::quiet_NaN(); // omega_0, required
    std::string initial = "reset";          // first iteration of a level: "reset" | "carry-over"
    double maxRelaxation = 1.0;             // |omega| <= max_relaxation
    double minRelaxation = 1e-3;            // |omega| >= min_relaxation; carry-over into [min, max]
    std::string negativeFactor = "restart"; // factor <= 0: "restart" (omega_0) | "keep" (sign)

    static const std::vector<std::string>& keys();
    static AitkenParameters parse(const config::Block& layer); // reads layer.<keyword> (required)
    void validate() const;
    std::string echo() const;
};

class Aitken final : public Accelerator
{
public:
    explicit Aitken(const AitkenParameters& params);
    std::string name() const override { return "aitken"; }
    void beginLevel() override;
    Eigen::VectorXd update(const Eigen::VectorXd& previousIterate,
                           const Eigen::VectorXd& solverOutput) override;
    void endLevel() override;
    double lastRelaxation() const override { return omega_; }
    // omega_0 and max_relaxation (not below min_relaxation) times factor.
    void scaleRelaxation(double factor) override;
    AcceleratorState saveState() const override;
    void loadState(const AcceleratorState& state) override;

private:
    double clamp(double omega, const char* what);
    double restart(double factor); // omega_0, with the note
    AitkenParameters params_;
    bool carryOver_;
    bool restartOnNegative_;
    int iteration_ = 0;
    double omega_ = std::numeric_limits<double>::quiet_NaN();
    double levelOmega_ = std::numeric_limits<double>::quiet_NaN(); // last omega of last level
    Eigen::VectorXd previousResidual_;
};

} // namespace fsi::acceleration
