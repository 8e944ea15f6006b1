// SPDX-License-Identifier: GPL-3.0-or-later
//
// The base of the quasi-Newton accelerators (after preCICE's BaseQNAcceleration). It keeps the
// secant columns, with r_i = u_hat_i - u_{i-1}:
//   V = [r_i - r_{i-1}, ...],  W = [u_hat_i - u_hat_{i-1}, ...]
// newest first: this level, then the last reuse_levels converged levels, at most max_columns;
// filters V by a QR decomposition (QrFilter.hpp) and leaves the update from the kept columns to
// the method (step()). The first update of a level uses constant relaxation
// u_i = u_{i-1} + omega_0 r_i (first_update "relaxation", the default) or, with
// first_update "quasi-newton", the method's step from the reused levels' columns when there are
// any (preCICE: initial relaxation not forced). With reused_on_growth "drop", once
// |r_i| > |r_{i-1}| within a level the reused columns are left out for the rest of that level
// (told in lastNote()). Any update whose V is empty or filtered away relaxes (told in
// lastNote()). A new method (e.g. IQN-IMVJ) is one class that implements step().
// Restart state: sizes = {n, L, m_1..m_L} (L stored levels, m_l columns), values = for each
// level V then W, column-major.
#pragma once

#include "acceleration/Accelerator.hpp"
#include "acceleration/QrFilter.hpp"

#include <deque>

namespace fsi::acceleration
{

// What every quasi-Newton method shares: the secant columns, their cap and reuse over levels,
// the QR filter and the relaxation of a level's first update.
struct QuasiNewtonParameters
{
    double initialRelaxation = std::numeric_limits<double>::quiet_NaN(); // omega_0, required
    int maxColumns = 100;             // cap on columns (current + reused), oldest dropped first
    int reuseLevels = 0;              // converged levels whose columns are reused (0 = none)
    double filterTolerance = 1e-3;    // QR filter epsilon, see QrFilter.hpp
    std::string filter = "qr-column"; // "qr-column" (|R_ii| < eps |v_i|) | "qr-matrix" (eps ||R||)
    std::string firstUpdate = "relaxation"; // a level's first update: "relaxation" (omega_0) |
                                            // "quasi-newton" (reused columns, if any)
    // When |r_i| > |r_{i-1}| within a level: "keep" the reused levels' columns (default) |
    // "drop" them for the rest of the level (their Jacobian no longer fits this level's map,
    // e.g. after a change of the time step of a viscoelastic solid).
    std::string reusedOnGrowth = "keep";

    // The keys above, for a method's keys() / parse() / echo() (a method may add its own).
    static const std::vector<std::string>& commonKeys();
    void parseCommon(const config::Block& b);
    std::string echoCommon() const; // "initial_relaxation: ..., filter_tolerance: ..."
    void validate() const;
};

class QuasiNewton : public Accelerator
{
public:
    void beginLevel() override;
    Eigen::VectorXd update(const Eigen::VectorXd& previousIterate,
                           const Eigen::VectorXd& solverOutput) final;
    void endLevel() override;
    double lastRelaxation() const override { return omega_; }
    // omega_0 of the first update of each level times factor.
    void scaleRelaxation(double factor) override { params_.initialRelaxation *= factor; }
    AcceleratorState saveState() const override;
    void loadState(const AcceleratorState& state) override;

    // Columns used by the last update (after the cap, before the filter) and those kept.
    int lastColumns() const { return lastColumns_; }
    int lastKeptColumns() const { return lastKept_; }

protected:
    explicit QuasiNewton(const QuasiNewtonParameters& params);

    // The method's update from the kept secant columns: V_kept = qr.q qr.r, w holds every
    // column (qr.kept indexes the kept ones), r_i and u_hat_i as above. Pre: qr.kept non-empty.
    virtual Eigen::VectorXd step(const FilteredQr& qr, const Eigen::MatrixXd& w,
                                 const Eigen::VectorXd& residual,
                                 const Eigen::VectorXd& solverOutput) = 0;

private:
    struct Columns
    {
        Eigen::MatrixXd v, w; // n x m, newest first
    };
    // Every column, newest first, at most max_columns (m > 0).
    void assembleColumns(Eigen::Index m, Eigen::MatrixXd& v, Eigen::MatrixXd& w) const;

    QuasiNewtonParameters params_;
    QrFilterKind filterKind_;
    std::deque<Eigen::VectorXd> currentV_, currentW_; // this level, newest first
    std::deque<Columns> past_;                        // converged levels, newest first
    Eigen::VectorXd previousResidual_, previousOutput_;
    int iteration_ = 0;
    bool reusedDropped_ = false; // this level ignores the reused columns (reused_on_growth)
    double omega_ = std::numeric_limits<double>::quiet_NaN();
    int lastColumns_ = 0, lastKept_ = 0;
};

} // namespace fsi::acceleration
