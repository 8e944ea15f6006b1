// SPDX-License-Identifier: GPL-3.0-or-later
// Error types of fsi::comm and the exit path for executables.
#pragma once

#include <stdexcept>
#include <string>

namespace fsi
{
namespace comm
{

class Channel;

// Exit codes used by the comm layer when it ends a run itself (watchdog, exitOnError).
constexpr int kExitError = 1;       // bad input, protocol or handshake mismatch
constexpr int kExitCommTimeout = 4; // the peer (or a local rank) stayed silent past the timeout
constexpr int kExitPeerAbort = 5;   // the peer sent Abort with a reason

// Base of every error thrown by fsi::comm. what() is one line. everyRank() is true when the
// error is raised on all ranks of this program at once (then only local rank 0 prints it).
class CommError : public std::runtime_error
{
public:
    explicit CommError(const std::string& what, bool everyRank = false, int localRank = 0)
        : std::runtime_error(what), everyRank_(everyRank), localRank_(localRank)
    {
    }
    bool everyRank() const { return everyRank_; }
    int localRank() const { return localRank_; }

private:
    bool everyRank_;
    int localRank_;
};

// A bounded wait expired: the peer exited, crashed or hangs. The run cannot continue cleanly
// (MPI requests are left pending), so exitOnError() ends it with MPI_Abort.
class TimeoutError : public CommError
{
public:
    using CommError::CommError;
};

// Received a wrong magic/version/kind, or the handshake found a mismatch. Raised on every rank
// of the side that detected it; the peer learns about it through an Abort message.
class ProtocolError : public CommError
{
public:
    using CommError::CommError;
};

// The peer sent Abort. reason() is the peer's text. Raised on every rank of the receiving side.
class PeerAbortError : public CommError
{
public:
    PeerAbortError(const std::string& peerName, const std::string& reason, bool everyRank,
                   int localRank);
    const std::string& reason() const { return reason_; }

private:
    std::string reason_;
};

// Whether every rank of this program caught the same error at the same point (e.g. a config
// check done on all ranks) or possibly only this rank.
enum class ErrorScope
{
    ThisRank,
    AllRanks,
};

// Call from the catch block in main. Prints "error: <what>" to stderr (once per program when
// the error is on every rank: local rank 0, or the program's first process before the channel
// exists; otherwise from each rank that caught it) and ends the process:
//  - TimeoutError, or an error not on every rank: tells the peer (best effort, bounded) and
//    calls MPI_Abort on the real MPI_COMM_WORLD with the exit code (mpirun stops the job);
//  - no channel yet (channel == nullptr) in an MPMD launch (multiProgramLaunch()): MPI_Abort
//    at once, so that the peer, waiting in the MPMD split or in MPI_Finalize, ends within a
//    second instead of at its timeout (the message is printed first);
//  - an error on every rank (CommError::everyRank() or scope == AllRanks): sends Abort(what)
//    to the peer unless the peer aborted first, closes the channel, finalises MPI and exits
//    with the code, so that both programs print their own message.
// Exit codes: kExitCommTimeout for TimeoutError, kExitPeerAbort for PeerAbortError, else
// kExitError. channel may be null (error before the coupling existed); keep the Channel alive
// outside the try block (std::optional<Channel>) so it can be passed here.
[[noreturn]] void exitOnError(const std::exception& error, Channel* channel,
                              ErrorScope scope = ErrorScope::ThisRank);

// Ends the process: flushes stdio, then MPI_Abort on the real MPI_COMM_WORLD when MPI is
// running, otherwise std::_Exit. Never returns.
[[noreturn]] void abortRun(int exitCode);

} // namespace comm
} // namespace fsi
