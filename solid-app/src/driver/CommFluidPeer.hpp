// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fluid peer over fsi::comm: the solid side of the coupling protocol spoken by fluid-app.
// The messages and their payloads are laid out in one place, fsi/comm/Protocol.hpp (shared with
// fluid-app); this class converts the wire's n x 3 row-major arrays to the driver's n x 3
// matrices (same layout) at the boundary. Displacements and forces are distributed rows: each
// fluid rank exchanges its own points and faces with rank 0 here (no gather on the fluid side).
#pragma once

#include "driver/FluidPeer.hpp"
#include "fsi/comm/Channel.hpp"

namespace fsi::driver
{

class CommFluidPeer : public FluidPeer
{
public:
    // Receives the fluid's interface geometry and its ranks' row maps (collective over the
    // solid's ranks). The channel
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
    // which global points / faces each fluid rank holds: displacements go to, and forces come
    // from, every fluid rank directly (Protocol.hpp; filled on rank 0)
    comm::RowMap pointRows_;
    comm::RowMap faceRows_;
    bool finished_ = false;
};

} // namespace fsi::driver
