// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fluid peer over fsi::comm: the solid side of the wire protocol spoken by fluid-app.
//   Hello (in Channel::open): fluid interfaceSizes = {points, faces}
//   InterfaceGeometry  fluid -> solid  values = points (3 P), face centres (3 F), area vectors (3 F)
//   Solve              solid -> fluid  values = point displacements (3 P) [m]; step = level,
//                                      iteration; scalars = {time [s]} (the fluid's own
//                                      accuracy) or {time, force tolerance, residual drop}
//                                      with integers = {min SIMPLE iterations} (FluidAccuracy)
//   Forces             fluid -> solid  values = face forces (3 F) [N]; integers = {SIMPLE
//                                      iterations[, converged 0/1]}; scalars = final residuals
//   Accept             solid -> fluid  step = level; scalars = {time [s]}
//   Finish / Abort(reason)
// All arrays are flat xyz per entity, in the fluid's global ordering.
#pragma once

#include "driver/FluidPeer.hpp"
#include "fsi/comm/Channel.hpp"

namespace fsi::driver
{

class CommFluidPeer : public FluidPeer
{
public:
    // Receives the fluid's interface geometry (collective over the solid's ranks). The channel
    // is not owned and must outlive the peer. Throws std::runtime_error for an inconsistent
    // geometry message.
    explicit CommFluidPeer(comm::Channel& channel);

    const FluidInterface& interface() const override { return interface_; }
    FluidResponse solve(int level, int iteration, double time,
                        const mapping::Values& pointDisplacement,
                        const FluidAccuracy& accuracy) override;
    void accept(int level, double time) override;
    void finish() override;
    void abort(const std::string& reason) noexcept override;

private:
    comm::Channel& channel_;
    FluidInterface interface_;
    bool finished_ = false;
};

} // namespace fsi::driver
