// SPDX-License-Identifier: GPL-3.0-or-later
// Solid-like comm test driver (the coupling driver and port-mode server): plays the solid
// part of CouplingScript.hpp. Usage: solid_like --launch port|mpmd [--port-file F]
// [--comm-timeout S] [driver flags]. Exit 0 when every check passed.
#include "CouplingScript.hpp"

using namespace fsi::comm;
using namespace fsi::comm::test;

namespace
{
void run(const LaunchOptions& launch, const DriverFlags& flags, std::optional<Channel>& slot)
{
    Identity self;
    self.role = Role::Solid;
    self.program = "solid-like";
    self.interfaceSizes =
        flags.interfaceSizes.empty() ? std::vector<std::int64_t>{5} : flags.interfaceSizes;
    self.protocolVersion = flags.protocolVersion;
    PeerExpectation expect;
    expect.program = flags.expectPeerProgram;
    expect.ranks = flags.expectPeerRanks;
    expect.interfaceSizes = flags.expectPeerSizes;
    slot.emplace(Channel::open(launch, self, expect));
    Channel& channel = *slot;
    FaultInjector inject(flags, channel);
    const int rank = channel.localRank();
    if (flags.handshakeOnly)
    {
        channel.send(MessageKind::Finish, 0, 0);
        channel.close();
        if (rank == 0)
            std::printf("solid-like: handshake complete with %s\n", channel.peerName().c_str());
        return;
    }

    inject.before("receive InterfaceGeometry");
    const Message geometry = channel.receive(MessageKind::InterfaceGeometry);
    const std::int64_t geometrySize = channel.peer().interfaceSizes.at(0);
    require(geometry.valueCount == geometrySize, "InterfaceGeometry count");
    for (std::size_t i = 0; i < geometry.values.size(); ++i)
        require(geometry.values[i] == geometryValue(static_cast<std::int64_t>(i)),
                "geometry value " + std::to_string(i));
    std::vector<RowShape> shapes;
    for (const std::int64_t n : kSizes)
    {
        shapes.push_back({n, 3, false}); // points: shared rows allowed
        shapes.push_back({n, 3, true});  // faces: a partition
    }
    const std::vector<RowMap> rowMaps = channel.receiveRowMaps(shapes);

    std::int64_t step = 0;
    int rounds = 0;
    int solves = 0;
    for (std::size_t round = 0; round < kSizes.size(); ++round)
    {
        const std::int64_t n = kSizes[round];
        ++step;
        for (std::int64_t iteration = 1; iteration <= 2; ++iteration)
        {
            std::vector<double> displacement;
            if (rank == 0)
            {
                displacement.resize(static_cast<std::size_t>(n));
                for (std::int64_t i = 0; i < n; ++i)
                    displacement[static_cast<std::size_t>(i)] =
                        displacementValue(i, step, iteration);
            }
            const bool wrongKind = inject.before("send Solve");
            channel.send(wrongKind ? MessageKind::Accept : MessageKind::Solve, step, iteration,
                         std::move(displacement));
            if (++solves == flags.dieBeforeRows)
            {
                std::fprintf(stderr, "solid-like: test: dying after Solve %d, before its rows\n",
                             solves);
                std::fflush(stderr);
                ::_exit(3);
            }
            if (!wrongKind)
            {
                std::vector<double> rows;
                if (rank == 0)
                    for (std::int64_t i = 0; i < n; ++i)
                        for (int c = 0; c < 3; ++c)
                            rows.push_back(rowDisplacement(i, c, step, iteration));
                channel.scatterRows(rowMaps[2 * round], rows);
            }
            inject.before("receive Forces");
            Message forces = channel.receive(MessageKind::Forces);
            require(forces.timeStep == step && forces.iteration == iteration &&
                        forces.valueCount == n,
                    "Forces header");
            require(forces.integers == std::vector<std::int64_t>{10 * step + iteration},
                    "Forces iteration count");
            require(forces.scalars == std::vector<double>{1.0e-3 / static_cast<double>(iteration),
                                                          2.5e-7 * static_cast<double>(step)},
                    "Forces residuals");
            channel.broadcastFromRoot(forces.values); // every rank checks the whole array
            require(static_cast<std::int64_t>(forces.values.size()) == n, "broadcast size");
            for (std::int64_t i = 0; i < n; ++i)
                require(forces.values[static_cast<std::size_t>(i)] ==
                            forceValue(displacementValue(i, step, iteration), i),
                        "force " + std::to_string(i) + " of level " + std::to_string(step));
            // every fluid rank's own rows, placed by the map
            const std::vector<double> faces = channel.gatherRows(rowMaps[2 * round + 1]);
            if (rank == 0)
            {
                require(static_cast<std::int64_t>(faces.size()) == 3 * n, "gathered rows size");
                for (std::int64_t i = 0; i < n; ++i)
                    for (int c = 0; c < 3; ++c)
                        require(faces[static_cast<std::size_t>(3 * i + c)] ==
                                    rowForce(i, c, step, iteration),
                                "force row " + std::to_string(i) + " of level " +
                                    std::to_string(step));
            }
            ++rounds;
        }
        inject.before("send Accept");
        channel.send(MessageKind::Accept, step, 0);
    }
    inject.before("send Finish");
    channel.send(MessageKind::Finish, step, 0);
    channel.close();
    if (rank == 0)
        std::printf("solid-like: exchange complete: %d rounds on %d ranks with %s\n", rounds,
                    channel.localSize(), channel.peerName().c_str());
}
} // namespace

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        const LaunchOptions launch = parseLaunchOptions(argc, argv);
        initialiseMpi(argc, argv);
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
