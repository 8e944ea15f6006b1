// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fluid solver as the coupling driver sees it: the driver commands, the fluid answers.
// The production implementation talks to fluid-app through fsi::comm (CommFluidPeer); unit
// tests of the driver layer may use a test double. Every call is made on ALL ranks of the
// solid's communicator (the transport is collective); arguments and results are significant
// on rank 0 only.
#pragma once

#include "driver/FluidAccuracy.hpp"
#include "mapping/Mapping.hpp"

#include <string>

namespace fsi::driver
{

// The fluid's interface geometry, in the fluid's global ordering, reference configuration [m].
struct FluidInterface
{
    mapping::PointCloud points;      // interface patch points: displacements are sent for these
    mapping::PointCloud faceCentres; // interface faces: forces come back for these
    mapping::PointCloud faceAreas;   // face area vectors [m^2], pointing out of the fluid
};

// One fluid answer to a SOLVE command.
struct FluidResponse
{
    mapping::Values faceForces; // force of the fluid ON the structure per face [N], faces x 3
    int iterations = 0;         // SIMPLE iterations used in this solve
    double initialResidual = 0; // largest initial residual of the solve (U, p)
    double finalResidual = 0;   // largest final residual
    bool converged = false;     // the asked accuracy was met (else: iteration cap hit)
    // > 0: a flow without a steady state, converged in the mean (faceForces are its mean over
    // the fluid's last iterations; fsiDict coupled.bandTolerance): the relative half-width of
    // the force's band
    double band = 0;
};

class FluidPeer
{
public:
    virtual ~FluidPeer() = default;
    // Significant on rank 0.
    virtual const FluidInterface& interface() const = 0;
    // Move the interface points by pointDisplacement (relative to the reference geometry,
    // points x 3 [m]) and solve the steady flow for level `level` at time `time` [s] to
    // `accuracy` (FluidAccuracy.hpp; driverControlled false: the fluid's own controls).
    virtual FluidResponse solve(int level, int iteration, double time,
                                const mapping::Values& pointDisplacement,
                                const FluidAccuracy& accuracy) = 0;
    // The level converged: the fluid writes its fields for this time.
    virtual void accept(int level, double time) = 0;
    // Normal end of the run.
    virtual void finish() = 0;
    // Abnormal end: the fluid stops with this reason; must not throw.
    virtual void abort(const std::string& reason) noexcept = 0;
};

} // namespace fsi::driver
