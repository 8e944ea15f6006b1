// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/Errors.hpp"

#include "Watchdog.hpp"
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/MpmdWorld.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mpi.h>
#include <thread>

namespace fsi::comm
{

PeerAbortError::PeerAbortError(const std::string& peerName, const std::string& reason,
                               bool everyRank, int localRank)
    : CommError("fsi::comm: " + peerName + " aborted the coupled run: " + reason, everyRank,
                localRank),
      reason_(reason)
{
}

void abortRun(int exitCode)
{
    std::fflush(stdout);
    std::fflush(stderr);
    int initialised = 0, finalised = 0;
    PMPI_Initialized(&initialised);
    PMPI_Finalized(&finalised);
    if (initialised && !finalised)
        PMPI_Abort(MPI_COMM_WORLD, exitCode);
    std::_Exit(exitCode);
}

void exitOnError(const std::exception& error, Channel* channel, ErrorScope scope)
{
    const auto* commError = dynamic_cast<const CommError*>(&error);
    const bool everyRank = (commError && commError->everyRank()) || scope == ErrorScope::AllRanks;
    const int localRank = commError && commError->everyRank() ? commError->localRank()
                          : channel                           ? channel->localRank()
                                                              : 0;
    // Before the channel exists the local rank is unknown: the program's first process prints.
    const LaunchShape shape = launchShape();
    const bool printer =
        !everyRank || (channel ? localRank == 0 : shape.worldRank == shape.firstWorldRank);
    if (printer)
        std::fprintf(stderr, "error: %s\n", error.what());
    std::fflush(stderr);

    const bool timeout = dynamic_cast<const TimeoutError*>(&error) != nullptr;
    const bool peerAbort = dynamic_cast<const PeerAbortError*>(&error) != nullptr;
    const int code = timeout ? kExitCommTimeout : peerAbort ? kExitPeerAbort : kExitError;

    // The peer is unresponsive or this program's ranks are not all here: stop everything.
    if (timeout || !everyRank)
    {
        if (channel && channel->healthy() && !channel->peerKnowsWeStop())
            channel->sendAbort(error.what());
        abortRun(code);
    }
    // No coupling yet in a one-mpirun (MPMD) launch: the peer waits in the MPMD split or in
    // MPI_Finalize, both collective over the whole job, until its timeout. End the job now; the
    // other ranks give the printing one a moment so that its message is not cut off.
    // (A failed handshake is known to both sides, which end in order: ProtocolError.)
    if (!channel && shape.programs > 1 && !dynamic_cast<const ProtocolError*>(&error))
    {
        if (!printer)
            std::this_thread::sleep_for(std::chrono::seconds(1));
        abortRun(code);
    }
    // Every rank of this program is here and the peer is reachable: end in order so that both
    // programs print their message and exit with their own code.
    if (channel)
    {
        if (channel->healthy() && !channel->peerKnowsWeStop())
            channel->sendAbort(error.what());
        if (channel->healthy())
            channel->close();
        else
            abortRun(code);
    }
    {
        // MPI_Finalize may wait for the peer (MPMD: one job); never longer than the timeout.
        detail::Watchdog guard(channel ? channel->options().timeoutSeconds : 60.0, {}, code);
        finaliseMpi();
    }
    std::exit(code);
}

} // namespace fsi::comm
