// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/Errors.hpp"

#include "Watchdog.hpp"
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/MpmdWorld.hpp"

#include <cstdio>
#include <cstdlib>
#include <mpi.h>

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
    if (!everyRank || localRank == 0)
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
