// SPDX-License-Identifier: GPL-3.0-or-later
//
// Inexact fluid solves steered by the driver (`coupling.fluid_accuracy`, DESIGN.md section 5).
// Polishing the flow against interface data that is still wrong is wasted work, so each SOLVE
// asks for an accuracy that follows the coupling residual (a forcing term in the spirit of
// Eisenstat-Walker and Birken's inexact fixed-point iteration):
//
//   eta_i = clamp(forcing_factor * r_est / u_scale, final.force_tolerance, max_force_tolerance)
//
// r_est is the expected interface residual of the iterate being sent (|r|/sqrt(n) of the
// previous coupling iteration; at a level's first iteration the first residual of the previous
// level), u_scale the RMS interface displacement of that iterate [m]. eta bounds the relative
// force error the fluid leaves: it stops once |F_k - F_{k-1}| rho / (1 - rho) <= eta |F_k|, rho
// the observed contraction of its force changes (the error left by a linearly converging
// iteration; a per-iteration change alone understates it by 1/(1 - rho), 20-50x for SIMPLE
// here), after min_iterations. A solve that meets eta = final.force_tolerance (and
// final.residual_drop) is "final"; a level is accepted only when its interface residual meets the
// tolerance AND its last fluid solve was final and converged. Without the block the fluid uses its
// own fsiDict `coupled` controls for every solve (each solve then counts as final).
#pragma once

#include <string>

namespace fsi::driver
{

// What one SOLVE asks of the fluid (sent with the command).
struct FluidAccuracy
{
    bool driverControlled = false; // false: the fluid's own fsiDict controls (nothing sent)
    double forceTolerance = 0.0;   // relative force change per SIMPLE iteration
    double residualDrop = 0.0;     // residuals <= drop x the solve's first residuals (0 = off)
    int minIterations = 1;         // SIMPLE iterations at least
    bool isFinal = true;           // the accuracy a level may be accepted on
};

struct FluidAccuracyParameters
{
    double finalForceTolerance = 2e-4; // final.force_tolerance
    double finalResidualDrop = 0.0;    // final.residual_drop (0 = off)
    double forcingFactor = 0.1;        // forcing_factor (c above)
    double maxForceTolerance = 1e-2;   // max_force_tolerance: the loosest accuracy asked
    int minIterations = 2;             // min_iterations per solve
    // Throws std::runtime_error naming coupling.fluid_accuracy.<key> and the fix.
    void validate() const;
};

class ForcingTerm
{
public:
    // params: nullptr = the block is absent (the fluid's own controls for every solve).
    explicit ForcingTerm(const FluidAccuracyParameters* params);

    // Accuracy for an iterate whose residual is expected to be expectedResidual (|r|/sqrt(n),
    // [m]; <= 0 or not finite: unknown, the loosest is asked) with RMS displacement
    // displacementScale [m].
    FluidAccuracy forIterate(double expectedResidual, double displacementScale) const;
    // The accuracy a level is accepted on.
    FluidAccuracy finalAccuracy() const;
    bool driverControlled() const { return controlled_; }
    std::string describe() const;

private:
    bool controlled_ = false;
    FluidAccuracyParameters params_;
};

} // namespace fsi::driver
