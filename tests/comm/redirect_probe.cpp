// SPDX-License-Identifier: GPL-3.0-or-later
// MPMD world redirect test (program A of `-np A redirect_probe A --launch mpmd : -np B
// solid_like --launch mpmd --handshake-only`). Links fsi_comm_world_redirect like fluid-app
// and a stand-in for libPstream (fake_pstream); checks that MPI_COMM_WORLD, as seen from both
// the executable and the shared library, is this program's A ranks, that an earlier MPI is
// accepted by MPI_Init_thread and finalised once, and that the coupling channel still works.
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/MpmdWorld.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

extern "C"
{
    int fakePstreamInitThread(int* argc, char*** argv, int* provided);
    int fakePstreamWorldSize();
    int fakePstreamWorldRank();
    int fakePstreamAllreduceSum(int value);
    int fakePstreamGathervRanks();
    int fakePstreamRing();
    int fakePstreamFinalize();
}

using namespace fsi::comm;

namespace
{
void require(bool ok, const std::string& what)
{
    if (!ok)
        throw std::runtime_error("redirect check failed: " + what);
}
} // namespace

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        const LaunchOptions launch = initialiseMpmdWorld(argc, argv);
        require(argc == 2, "usage: redirect_probe RANKS_OF_THIS_PROGRAM --launch mpmd");
        const int expected = std::stoi(argv[1]);

        int provided = -1;
        require(fakePstreamInitThread(&argc, &argv, &provided) == MPI_SUCCESS,
                "MPI_Init_thread after our MPI_Init_thread must succeed");
        int realWorld = 0, size = 0, rank = 0;
        PMPI_Comm_size(MPI_COMM_WORLD, &realWorld);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        require(size == expected,
                "MPI_Comm_size(MPI_COMM_WORLD) in the executable is " + std::to_string(size));
        require(fakePstreamWorldSize() == expected,
                "MPI_Comm_size(MPI_COMM_WORLD) in a shared library is " +
                    std::to_string(fakePstreamWorldSize()));
        require(fakePstreamWorldRank() == rank, "ranks differ between executable and library");
        const int sum = fakePstreamAllreduceSum(rank + 1);
        require(sum == expected * (expected + 1) / 2, "allreduce sum " + std::to_string(sum));
        require(fakePstreamGathervRanks() == 1, "gatherv order");
        const int left = fakePstreamRing();
        require(left == (rank + expected - 1) % expected, "ring neighbour " + std::to_string(left));
        if (rank == 0)
            std::printf("redirect_probe: MPI_COMM_WORLD has %d ranks (real world %d), allreduce "
                        "%d, gatherv and ring ok\n",
                        size, realWorld, sum);

        Identity self;
        self.role = Role::Fluid;
        self.program = "redirect_probe";
        channel.emplace(Channel::open(launch, self));
        channel->receive(MessageKind::Finish);
        channel->close();
        require(fakePstreamFinalize() == MPI_SUCCESS, "first MPI_Finalize");
        require(fakePstreamFinalize() == MPI_SUCCESS, "second MPI_Finalize must be accepted");
        int finalised = 0;
        MPI_Finalized(&finalised);
        require(finalised == 1, "MPI finalised");
        if (rank == 0)
            std::printf("redirect_probe: channel with %s ok, MPI finalised once\n",
                        channel->peerName().c_str());
        return 0;
    }
    catch (const std::exception& e)
    {
        exitOnError(e, channel ? &*channel : nullptr);
    }
}
