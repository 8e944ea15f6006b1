// SPDX-License-Identifier: GPL-3.0-or-later
// Fluid-like comm test driver: links the MPMD world redirect as fluid-app does and plays the
// fluid part of CouplingScript.hpp. Usage: fluid_like --launch port|mpmd [--port-file F]
// [--comm-timeout S] [driver flags, see CouplingScript.hpp]. Exit 0 when every check passed.
#include "CouplingScript.hpp"

#include "fsi/comm/Collectives.hpp"

using namespace fsi::comm;
using namespace fsi::comm::test;

namespace
{
void run(const LaunchOptions& launch, const DriverFlags& flags, std::optional<Channel>& slot)
{
    if (flags.checkWorldSize > 0)
    {
        // Redirect check as OpenFOAM's Pstream would see it.
        int size = 0, one = 1, sum = 0;
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        MPI_Allreduce(&one, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        require(size == flags.checkWorldSize && sum == flags.checkWorldSize,
                "MPI_COMM_WORLD size " + std::to_string(size) + ", allreduce " +
                    std::to_string(sum) + ", expected " + std::to_string(flags.checkWorldSize));
    }
    Identity self;
    self.role = Role::Fluid;
    self.program = "fluid-like";
    self.interfaceSizes = flags.interfaceSizes.empty()
                              ? std::vector<std::int64_t>{flags.geometrySize}
                              : flags.interfaceSizes;
    self.protocolVersion = flags.protocolVersion;
    PeerExpectation expect;
    expect.ranks = flags.expectPeerRanks;
    expect.interfaceSizes = flags.expectPeerSizes;
    slot.emplace(Channel::open(launch, self, expect));
    Channel& channel = *slot;
    FaultInjector inject(flags, channel);
    const int rank = channel.localRank();
    const int size = channel.localSize();
    if (flags.handshakeOnly)
    {
        channel.receive(MessageKind::Finish);
        channel.close();
        if (rank == 0)
            std::printf("fluid-like: handshake complete with %s\n", channel.peerName().c_str());
        return;
    }

    // Interface geometry, distributed over the fluid ranks, gathered and sent.
    std::vector<double> local;
    const std::int64_t g0 = blockStart(flags.geometrySize, size, rank);
    for (std::int64_t k = 0; k < blockCount(flags.geometrySize, size, rank); ++k)
        local.push_back(geometryValue(g0 + k));
    Message geometry;
    geometry.kind = MessageKind::InterfaceGeometry;
    geometry.values = channel.gatherToRoot(local);
    inject.before("send InterfaceGeometry");
    channel.send(geometry);
    std::vector<std::vector<std::int64_t>> rowMaps = rowMapsOf(size, rank);
    if (flags.overlapFaceRows && rank == size - 1)
        rowMaps[5].push_back(0);
    channel.sendRowMaps(rowMaps);

    std::int64_t step = 0;
    int rounds = 0;
    for (std::size_t round = 0; round < kSizes.size(); ++round)
    {
        const std::int64_t n = kSizes[round];
        const std::vector<std::int64_t>& pointRows = rowMaps[2 * round];
        const std::vector<std::int64_t>& faceRows = rowMaps[2 * round + 1];
        ++step;
        for (std::int64_t iteration = 1; iteration <= 2; ++iteration)
        {
            inject.before("receive Solve");
            const Message solve = channel.receive(MessageKind::Solve);
            require(solve.timeStep == step && solve.iteration == iteration && solve.valueCount == n,
                    "Solve header step/iteration/count");
            const std::int64_t start = blockStart(n, size, rank);
            const std::vector<double> mine =
                channel.scatterFromRoot(solve.values, blockCount(n, size, rank));
            std::vector<double> forces(mine.size());
            for (std::size_t k = 0; k < mine.size(); ++k)
            {
                const std::int64_t i = start + static_cast<std::int64_t>(k);
                require(mine[k] == displacementValue(i, step, iteration),
                        "displacement " + std::to_string(i) + " of level " + std::to_string(step));
                forces[k] = forceValue(mine[k], i);
            }
            // this rank's rows straight from the solid's root
            const std::vector<double> own =
                channel.receiveOwnRows(3 * static_cast<std::int64_t>(pointRows.size()));
            for (std::size_t j = 0; j < pointRows.size(); ++j)
                for (int c = 0; c < 3; ++c)
                    require(own[3 * j + static_cast<std::size_t>(c)] ==
                                rowDisplacement(pointRows[j], c, step, iteration),
                            "displacement row " + std::to_string(pointRows[j]) + " of level " +
                                std::to_string(step));
            std::vector<double> ownForces(3 * faceRows.size());
            for (std::size_t j = 0; j < faceRows.size(); ++j)
                for (int c = 0; c < 3; ++c)
                    ownForces[3 * j + static_cast<std::size_t>(c)] =
                        rowForce(faceRows[j], c, step, iteration);
            Message reply;
            reply.kind = MessageKind::Forces;
            reply.timeStep = step;
            reply.iteration = iteration;
            reply.values = channel.gatherToRoot(forces);
            reply.integers = {10 * step + iteration};
            reply.scalars = {1.0e-3 / static_cast<double>(iteration),
                             2.5e-7 * static_cast<double>(step)};
            inject.before("send Forces");
            channel.send(reply);
            channel.sendOwnRows(ownForces);
            ++rounds;
        }
        inject.before("receive Accept");
        const Message accept = channel.receive(MessageKind::Accept);
        require(accept.timeStep == step && accept.valueCount == 0, "Accept header");
    }
    inject.before("receive Finish");
    channel.receive(MessageKind::Finish);
    channel.close();
    if (rank == 0)
        std::printf("fluid-like: exchange complete: %d rounds on %d ranks with %s\n", rounds, size,
                    channel.peerName().c_str());
}

} // namespace

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        const LaunchOptions launch = initialiseMpmdWorld(argc, argv);
        const DriverFlags flags = parseDriverFlags(argc, argv);
        run(launch, flags, channel);
        finaliseMpi();
        return 0;
    }
    catch (const CollectiveTestError& e)
    {
        exitOnError(e, channel ? &*channel : nullptr, ErrorScope::AllRanks);
    }
    catch (const std::exception& e)
    {
        exitOnError(e, channel ? &*channel : nullptr);
    }
}
