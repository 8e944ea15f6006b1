// SPDX-License-Identifier: GPL-3.0-or-later
// MPMD world redirect against the real OpenFOAM v1912 libPstream.so (no OpenFOAM headers
// needed: the three entry points are declared here with their exact signatures).
// Run as `-np A pstream_probe A --launch mpmd : -np B solid_like --launch mpmd
// --handshake-only --expect-peer-program pstream_probe`: after initialiseMpmdWorld, OpenFOAM's
// UPstream::init must accept the running MPI and Foam::reduce over OpenFOAM's world
// communicator must sum over the A fluid ranks only; UPstream::exit(0) finalises once.
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/MpmdWorld.hpp"

#include <cstdio>
#include <optional>
#include <string>

namespace Foam
{
template <class T> class sumOp;
class UPstream
{
public:
    static bool init(int& argc, char**& argv, const bool needsThread);
    static void exit(int errnum);
};
void reduce(double& value, const sumOp<double>& op, const int tag, const int communicator);
} // namespace Foam

using namespace fsi::comm;

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        const LaunchOptions launch = initialiseMpmdWorld(argc, argv); // before OpenFOAM
        if (argc != 2)
            throw std::runtime_error("usage: pstream_probe RANKS_OF_THIS_PROGRAM --launch mpmd");
        const int expected = std::stoi(argv[1]);
        Foam::UPstream::init(argc, argv, false); // what argList does for -parallel
        double ranks = 1.0;
        const char noState = 0; // sumOp<double> is an empty function object
        Foam::reduce(ranks, reinterpret_cast<const Foam::sumOp<double>&>(noState), 1, 0);
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        if (ranks != static_cast<double>(expected))
            throw std::runtime_error("Foam::reduce over OpenFOAM's world summed " +
                                     std::to_string(ranks) + " ranks, expected " +
                                     std::to_string(expected));
        if (rank == 0)
            std::printf("pstream_probe: Foam::reduce over OpenFOAM's world counts %g ranks\n",
                        ranks);
        Identity self;
        self.role = Role::Fluid;
        self.program = "pstream_probe";
        channel.emplace(Channel::open(launch, self));
        channel->receive(MessageKind::Finish);
        channel->close();
        if (rank == 0)
            std::printf("pstream_probe: channel with %s ok; UPstream::exit(0)\n",
                        channel->peerName().c_str());
        std::fflush(stdout);
        channel.reset();
        Foam::UPstream::exit(0); // MPI_Finalize through the redirect, then ::exit(0)
    }
    catch (const std::exception& e)
    {
        exitOnError(e, channel ? &*channel : nullptr);
    }
}
