// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/Channel.hpp"

#include "Watchdog.hpp"
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/comm/PortFile.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace fsi::comm
{

namespace
{
constexpr int kTagHeader = 7101;
constexpr int kTagPayload = 7102;
constexpr int kTagIntercomm = 7100;
constexpr int kTagRowMap = 7103; // distributed side rank -> whole side root, once
constexpr int kTagRows = 7104;   // interface rows, either way, per Solve / Forces

// Status word of the root's local broadcast.
enum Status : std::int64_t
{
    kOk = 0,
    kTimeout = 1,
    kProtocol = 2,
    kPeerAbort = 3,
    kOther = 4,
};

using Clock = std::chrono::steady_clock;

std::string seconds(double s)
{
    std::ostringstream out;
    out << s << " s";
    return out.str();
}

// Non-root ranks wait for the root, who itself waits up to the timeout for the peer.
double nonRootBound(double timeout)
{
    return timeout + std::max(2.0, 0.1 * timeout);
}

// Root -> all ranks: a status word and bytes (payload or error text). Bounded.
void shareFromRoot(MPI_Comm comm, int size, std::int64_t& status, std::vector<char>& bytes,
                   double firstWait, double timeout, const std::string& what)
{
    if (size == 1)
        return;
    std::int64_t head[2] = {status, static_cast<std::int64_t>(bytes.size())};
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Ibcast(head, 2, MPI_INT64_T, 0, comm, &request), what);
    waitBounded(request, firstWait, what + " (local broadcast from rank 0)");
    status = head[0];
    bytes.resize(static_cast<std::size_t>(head[1]));
    if (head[1] > 0)
    {
        checkMpi(MPI_Ibcast(bytes.data(), static_cast<int>(head[1]), MPI_CHAR, 0, comm, &request),
                 what);
        waitBounded(request, timeout, what + " (local broadcast from rank 0)");
    }
}

[[noreturn]] void throwStatus(std::int64_t status, const std::string& text, int rank,
                              const std::string& peerName)
{
    switch (status)
    {
    case kTimeout:
        throw TimeoutError(text, true, rank);
    case kProtocol:
        throw ProtocolError(text, true, rank);
    case kPeerAbort:
        throw PeerAbortError(peerName, text, true, rank);
    default:
        throw CommError(text, true, rank);
    }
}

std::int64_t statusOf(const std::exception& e)
{
    if (dynamic_cast<const TimeoutError*>(&e))
        return kTimeout;
    if (dynamic_cast<const ProtocolError*>(&e))
        return kProtocol;
    if (dynamic_cast<const PeerAbortError*>(&e))
        return kPeerAbort;
    return kOther;
}

// Work done on the local root only, as every local rank learns it. On the root `work` runs and
// returns the bytes the other ranks need; an exception becomes its status word and its text (a
// PeerAbortError: the peer's own reason). Then every rank holds the root's status and bytes
// (shareFromRoot, bounded; a failure of the sharing itself propagates).
struct RootOutcome
{
    std::int64_t status = kOk;
    std::vector<char> bytes;
};

RootOutcome runOnRootAndShare(MPI_Comm comm, int size, bool root,
                              const std::function<std::vector<char>()>& work, double firstWait,
                              double timeout, const std::string& what)
{
    RootOutcome outcome;
    if (root)
    {
        try
        {
            outcome.bytes = work();
        }
        catch (const PeerAbortError& e)
        {
            outcome.status = kPeerAbort;
            outcome.bytes.assign(e.reason().begin(), e.reason().end());
        }
        catch (const std::exception& e)
        {
            outcome.status = statusOf(e);
            const std::string text = e.what();
            outcome.bytes.assign(text.begin(), text.end());
        }
    }
    shareFromRoot(comm, size, outcome.status, outcome.bytes, firstWait, timeout, what);
    return outcome;
}

// Every rank throws the root's error alike (its kind and text), or returns.
void throwIfFailed(const RootOutcome& outcome, int rank, const std::string& peerName)
{
    if (outcome.status != kOk)
        throwStatus(outcome.status, std::string(outcome.bytes.begin(), outcome.bytes.end()), rank,
                    peerName);
}

std::string readFile(const std::string& path, bool& exists)
{
    std::ifstream in(path, std::ios::binary);
    exists = static_cast<bool>(in);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Root-to-root transfer of one message (header, then payload if any). Bounded.
void sendRaw(MPI_Comm inter, const Message& message, std::int32_t version, double timeout,
             const std::string& peerName)
{
    MessageHeader header = headerOf(message);
    header.version = version;
    const EncodedHeader words = encodeHeader(header);
    const std::vector<char> payload = encodePayload(message);
    const std::string what = "sending " + toString(message.kind) + " to " + peerName;
    auto wait = [&](MPI_Request& request)
    {
        try
        {
            waitBounded(request, timeout, what);
        }
        catch (const TimeoutError&)
        {
            // Even a small (eager) send can stay incomplete when the peer's connection broke.
            throw TimeoutError("fsi::comm: " + what + ": not taken within " + seconds(timeout) +
                               "; the peer exited, crashed or hangs");
        }
    };
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Isend(words.data(), kHeaderWords, MPI_INT64_T, 0, kTagHeader, inter, &request),
             what);
    wait(request);
    if (!payload.empty())
    {
        checkMpi(MPI_Isend(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, 0,
                           kTagPayload, inter, &request),
                 what);
        wait(request);
    }
}

// Receives one message from the peer root. The peer's protocol version is returned in
// peerVersion when given (the caller checks it); otherwise it is checked here, after the payload
// arrived, so the message stream stays in step even on a mismatch.
Message receiveRaw(MPI_Comm inter, std::int32_t version, double timeout,
                   const std::string& waitWhat, std::int32_t* peerVersion = nullptr)
{
    EncodedHeader words{};
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Irecv(words.data(), kHeaderWords, MPI_INT64_T, 0, kTagHeader, inter, &request),
             waitWhat);
    try
    {
        waitBounded(request, timeout, waitWhat);
    }
    catch (const TimeoutError&)
    {
        MPI_Cancel(&request);
        throw TimeoutError("fsi::comm: " + waitWhat + ": nothing received within " +
                           seconds(timeout) + "; the peer exited, crashed or hangs");
    }
    const MessageHeader header = decodeHeader(words, static_cast<std::int32_t>(words[1]));
    Message message;
    const std::int64_t bytes =
        header.valueCount * 8 + header.scalarCount * 8 + header.integerCount * 8 + header.textBytes;
    std::vector<char> payload(static_cast<std::size_t>(bytes));
    if (bytes > 0)
    {
        if (bytes > INT32_MAX)
            throw ProtocolError("fsi::comm: message payload too large");
        checkMpi(MPI_Irecv(payload.data(), static_cast<int>(bytes), MPI_CHAR, 0, kTagPayload, inter,
                           &request),
                 waitWhat);
        try
        {
            waitBounded(request, timeout, waitWhat);
        }
        catch (const TimeoutError&)
        {
            MPI_Cancel(&request);
            throw TimeoutError("fsi::comm: " + waitWhat + ": payload of " + toString(header.kind) +
                               " not received within " + seconds(timeout) +
                               "; the peer exited, crashed or hangs");
        }
    }
    decodePayload(header, payload, message);
    if (peerVersion)
        *peerVersion = header.version;
    else
        decodeHeader(words, version); // throws ProtocolError on a version mismatch
    return message;
}

// A message count for MPI (int); CommError beyond 2^31 - 1 elements.
int messageCount(std::size_t n, const std::string& what)
{
    if (n > static_cast<std::size_t>(INT32_MAX))
        throw CommError("fsi::comm: " + what + ": more than 2^31 - 1 values in one message");
    return static_cast<int>(n);
}

enum class Transfer
{
    Send,
    Receive,
};

// waitBounded for a transfer with the peer: a timeout blames the peer, on this rank. A pending
// receive is cancelled; a send is not (cancelling sends is deprecated in MPI 4).
void waitForPeer(MPI_Request& request, double timeout, const std::string& what, int rank,
                 Transfer transfer, MPI_Status* status = MPI_STATUS_IGNORE)
{
    try
    {
        waitBounded(request, timeout, what, status);
    }
    catch (const TimeoutError&)
    {
        if (transfer == Transfer::Receive)
            MPI_Cancel(&request);
        throw TimeoutError("fsi::comm: " + what + ": not complete within " + seconds(timeout) +
                               "; the peer exited, crashed or hangs",
                           false, rank);
    }
}

// Bounded receive of one message of unknown length (elements of `type`, T-sized) from
// `source`: probes until it arrives, then receives exactly its size.
template <class T>
std::vector<T> receiveSized(MPI_Comm comm, int source, int tag, MPI_Datatype type, double timeout,
                            const std::string& what, int rank)
{
    MPI_Status status;
    const bool arrived = pollUntil(
        [&]
        {
            int flag = 0;
            checkMpi(MPI_Iprobe(source, tag, comm, &flag, &status), what);
            return flag != 0;
        },
        timeout);
    if (!arrived)
        throw TimeoutError("fsi::comm: " + what + ": nothing received within " + seconds(timeout) +
                               "; the peer exited, crashed or hangs",
                           false, rank);
    int count = 0;
    checkMpi(MPI_Get_count(&status, type, &count), what);
    std::vector<T> values(static_cast<std::size_t>(count));
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Irecv(values.data(), count, type, source, tag, comm, &request), what);
    waitForPeer(request, timeout, what, rank, Transfer::Receive);
    return values;
}

void put64(std::vector<char>& out, std::int64_t v)
{
    const char* p = reinterpret_cast<const char*>(&v);
    out.insert(out.end(), p, p + 8);
}

std::int64_t get64(const std::vector<char>& in, std::size_t& at)
{
    std::int64_t v = 0;
    if (at + 8 > in.size())
        throw CommError("fsi::comm: internal: short local broadcast");
    std::memcpy(&v, in.data() + at, 8);
    at += 8;
    return v;
}

std::string describe(const std::vector<std::int64_t>& sizes)
{
    std::string out = "[";
    for (std::size_t i = 0; i < sizes.size(); ++i)
        out += (i ? ", " : "") + std::to_string(sizes[i]);
    return out + "]";
}
} // namespace

std::string toString(Role role)
{
    return role == Role::Fluid ? "fluid" : "solid";
}

Channel::Channel(Channel&& other) noexcept
    : options_(other.options_), self_(other.self_), peer_(other.peer_),
      peerKnown_(other.peerKnown_), localComm_(other.localComm_), interComm_(other.interComm_),
      localRank_(other.localRank_), localSize_(other.localSize_), healthy_(other.healthy_),
      closed_(other.closed_), peerKnowsWeStop_(other.peerKnowsWeStop_)
{
    other.localComm_ = MPI_COMM_NULL;
    other.interComm_ = MPI_COMM_NULL;
    other.closed_ = true;
}

Channel::~Channel()
{
    int finalised = 0;
    PMPI_Finalized(&finalised);
    if (closed_ || !healthy_ || finalised)
        return;
    // Not closed: release locally without talking to the peer (never blocks).
    if (interComm_ != MPI_COMM_NULL)
        MPI_Comm_free(&interComm_);
    if (localComm_ != MPI_COMM_NULL)
        MPI_Comm_free(&localComm_);
}

std::string Channel::peerName() const
{
    if (!peerKnown_)
        return "the " + toString(self_.role == Role::Fluid ? Role::Solid : Role::Fluid) +
               " program";
    return peer_.program + " (" + toString(peer_.role) + ", " + std::to_string(peer_.ranks) +
           (peer_.ranks == 1 ? " rank)" : " ranks)");
}

void Channel::fail()
{
    healthy_ = false;
}

Channel Channel::open(const LaunchOptions& options, const Identity& self,
                      const PeerExpectation& expectation)
{
    if (!(options.timeoutSeconds > 0.0 && options.timeoutSeconds <= kMaxTimeoutSeconds))
        throw CommError("fsi::comm: a timeout of " + seconds(options.timeoutSeconds) +
                            " is outside (0, 1e9] s; give --comm-timeout (or the config's "
                            "timeout) of at most 1e9 s",
                        true);
    // A write to the socket of a dead peer (port mode: TCP between two mpiruns) must fail with
    // EPIPE and reach our error path, not kill this process silently by SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    Channel channel;
    channel.options_ = options;
    channel.self_ = self;
    if (channel.self_.program.empty())
        channel.self_.program = toString(self.role);
    if (options.mode == LaunchMode::Port)
        channel.connectPort();
    else
        channel.connectMpmd();
    try
    {
        channel.handshake(expectation);
    }
    catch (const ProtocolError& e)
    {
        // Both sides know the handshake failed: end the connection in order, then report.
        if (e.everyRank())
        {
            channel.peerKnowsWeStop_ = true;
            channel.close();
        }
        else
        {
            channel.fail();
        }
        throw;
    }
    catch (...)
    {
        channel.fail();
        throw;
    }
    return channel;
}

void Channel::connectMpmd()
{
    const MpmdLayout& layout = mpmdLayout(options_.timeoutSeconds);
    checkMpi(MPI_Comm_dup(layout.programComm, &localComm_), "MPI_Comm_dup");
    MPI_Comm_set_errhandler(localComm_, MPI_ERRORS_RETURN);
    MPI_Comm_rank(localComm_, &localRank_);
    MPI_Comm_size(localComm_, &localSize_);
    const int remoteLeader = layout.appLeaders[static_cast<std::size_t>(1 - layout.appNumber)];
    {
        detail::Watchdog guard(options_.timeoutSeconds,
                               isRoot() ? "fsi::comm: MPMD coupling with " + peerName() +
                                              " (MPI_Intercomm_create) did not complete within " +
                                              seconds(options_.timeoutSeconds) +
                                              "; the peer exited, crashed or never opened its "
                                              "coupling"
                                        : std::string(),
                               kExitCommTimeout);
        checkMpi(MPI_Intercomm_create(localComm_, 0, MPI_COMM_WORLD, remoteLeader, kTagIntercomm,
                                      &interComm_),
                 "MPI_Intercomm_create");
    }
    MPI_Comm_set_errhandler(interComm_, MPI_ERRORS_RETURN);
}

void Channel::connectPort()
{
    // Port mode is for two separate mpiruns. Inside one MPMD mpirun the peer (given --launch
    // mpmd) would wait in the MPMD split: say so now instead of timing out without a word.
    if (const LaunchShape shape = launchShape(); shape.programs > 1)
        throw CommError("fsi::comm: " + self_.program +
                            " was given --launch port, but its mpirun started " +
                            std::to_string(shape.programs) +
                            " programs (an MPMD launch): give both programs --launch mpmd, or "
                            "start them with two mpiruns (scripts/launch-port)",
                        true);
    checkMpi(PMPI_Comm_dup(MPI_COMM_WORLD, &localComm_), "MPI_Comm_dup");
    MPI_Comm_set_errhandler(localComm_, MPI_ERRORS_RETURN);
    MPI_Comm_rank(localComm_, &localRank_);
    MPI_Comm_size(localComm_, &localSize_);
    const double timeout = options_.timeoutSeconds;
    const std::string& path = options_.portFile;
    char portName[MPI_MAX_PORT_NAME + 1] = {};

    if (self_.role == Role::Solid)
    {
        // Server: open a port and publish it.
        const RootOutcome setUp = runOnRootAndShare(
            localComm_, localSize_, isRoot(),
            [&]
            {
                checkMpi(MPI_Open_port(MPI_INFO_NULL, portName), "MPI_Open_port");
                PortFileRecord record;
                record.portName = portName;
                record.pid = static_cast<long>(getpid());
                record.host = thisHostName();
                record.createdSeconds = std::chrono::duration<double>(
                                            std::chrono::system_clock::now().time_since_epoch())
                                            .count();
                writePortFileAtomically(path, record);
                return std::vector<char>();
            },
            timeout, timeout, "port set-up");
        throwIfFailed(setUp, localRank_, peerName());
        {
            detail::Watchdog guard(
                timeout,
                isRoot() ? "fsi::comm: no fluid program connected within " + seconds(timeout) +
                               " to the port published in " + path +
                               "; start it with --launch port --port-file " + path +
                               " (two mpiruns also need the same --ompi-server, see "
                               "scripts/launch-port)"
                         : std::string(),
                kExitCommTimeout, isRoot() ? path : std::string());
            checkMpi(MPI_Comm_accept(isRoot() ? portName : nullptr, MPI_INFO_NULL, 0, localComm_,
                                     &interComm_),
                     "MPI_Comm_accept");
        }
        if (isRoot())
        {
            std::remove(path.c_str()); // connected: the file has served its purpose
            MPI_Close_port(portName);
        }
    }
    else
    {
        // Client: wait for the file, check it, connect.
        const RootOutcome found = runOnRootAndShare(
            localComm_, localSize_, isRoot(),
            [&]
            {
                const auto start = Clock::now();
                const auto limit = std::chrono::duration<double>(timeout);
                const auto staleGrace = std::chrono::duration<double>(std::min(timeout, 3.0));
                std::string staleSince;
                auto staleSeen = start;
                std::string lastText;
                for (;;)
                {
                    bool exists = false;
                    const std::string text = readFile(path, exists);
                    if (exists)
                    {
                        const PortFileRecord record = parsePortFile(text, path);
                        const std::string stale = staleReason(record);
                        if (stale.empty())
                        {
                            std::snprintf(portName, sizeof(portName), "%s",
                                          record.portName.c_str());
                            break;
                        }
                        // A new server may be about to replace the file: allow a short grace.
                        if (staleSince.empty() || text != lastText)
                        {
                            staleSince = stale;
                            staleSeen = Clock::now();
                            lastText = text;
                        }
                        if (Clock::now() - staleSeen > staleGrace)
                        {
                            throw CommError("port file " + path + " is stale: " + staleSince +
                                            "; delete it and restart the solid (server) side");
                        }
                    }
                    if (Clock::now() - start > limit)
                    {
                        throw TimeoutError(
                            "fsi::comm: port file " + path + " did not appear within " +
                            seconds(timeout) +
                            "; start the solid (server) with --launch port --port-file " + path);
                    }
                    std::this_thread::sleep_for(std::chrono::milliseconds(50));
                }
                return std::vector<char>();
            },
            nonRootBound(timeout), timeout, "port file");
        throwIfFailed(found, localRank_, peerName());
        {
            detail::Watchdog guard(
                timeout,
                isRoot() ? "fsi::comm: connecting to the port in " + path +
                               " did not complete within " + seconds(timeout) +
                               "; the solid (server) exited or hangs, or the two mpiruns do not "
                               "share an ompi-server (see scripts/launch-port)"
                         : std::string(),
                kExitCommTimeout);
            checkMpi(MPI_Comm_connect(isRoot() ? portName : nullptr, MPI_INFO_NULL, 0, localComm_,
                                      &interComm_),
                     "MPI_Comm_connect to the port in " + path +
                         " (is the solid still accepting? two mpiruns need the same "
                         "--ompi-server, see scripts/launch-port)");
        }
    }
    MPI_Comm_set_errhandler(interComm_, MPI_ERRORS_RETURN);
}

void Channel::handshake(const PeerExpectation& expectation)
{
    const double timeout = options_.timeoutSeconds;
    const RootOutcome shaken = runOnRootAndShare(
        localComm_, localSize_, isRoot(),
        [&]
        {
            int remoteSize = 0;
            MPI_Comm_remote_size(interComm_, &remoteSize);
            std::string ourReason;
            std::string peerReason;
            Message hello;
            hello.kind = MessageKind::Hello;
            hello.integers = {static_cast<std::int64_t>(self_.role), localSize_};
            hello.integers.insert(hello.integers.end(), self_.interfaceSizes.begin(),
                                  self_.interfaceSizes.end());
            hello.text = self_.program;
            sendRaw(interComm_, hello, self_.protocolVersion, timeout, peerName());
            try
            {
                std::int32_t peerVersion = 0;
                const Message reply = receiveRaw(
                    interComm_, self_.protocolVersion, timeout,
                    "waiting for the handshake (Hello) from " + peerName(), &peerVersion);
                if (reply.kind != MessageKind::Hello || reply.integers.size() < 2)
                    throw ProtocolError("fsi::comm: expected Hello from the peer, got " +
                                        toString(reply.kind));
                peer_.role = static_cast<Role>(reply.integers[0]);
                peer_.ranks = static_cast<int>(reply.integers[1]);
                peer_.interfaceSizes.assign(reply.integers.begin() + 2, reply.integers.end());
                peer_.program = reply.text;
                peerKnown_ = true;
                const std::string who = peerName();
                if (peerVersion != self_.protocolVersion)
                    ourReason = "protocol version mismatch: " + who + " speaks version " +
                                std::to_string(peerVersion) + ", " + self_.program + " version " +
                                std::to_string(self_.protocolVersion) +
                                "; build both programs from the same source";
                else if (peer_.role != Role::Fluid && peer_.role != Role::Solid)
                    ourReason = "the peer announced an unknown role";
                else if (peer_.role == self_.role)
                    ourReason = "both programs are " + toString(self_.role) +
                                " programs; couple one fluid with one solid";
                else if (peer_.ranks != remoteSize)
                    ourReason = who + " announced " + std::to_string(peer_.ranks) +
                                " ranks but the intercommunicator has " +
                                std::to_string(remoteSize);
                else if (!expectation.program.empty() && peer_.program != expectation.program)
                    ourReason = "peer program is '" + peer_.program + "', " + self_.program +
                                " expects '" + expectation.program + "'";
                else if (expectation.ranks > 0 && peer_.ranks != expectation.ranks)
                    ourReason = "rank layout mismatch: " + who + " runs on " +
                                std::to_string(peer_.ranks) + " ranks, " + self_.program +
                                " expects " + std::to_string(expectation.ranks);
                else if (!expectation.interfaceSizes.empty() &&
                         peer_.interfaceSizes != expectation.interfaceSizes)
                    ourReason = "interface size mismatch: " + who + " announced " +
                                describe(peer_.interfaceSizes) + ", " + self_.program +
                                " expects " + describe(expectation.interfaceSizes);
            }
            catch (const ProtocolError& e)
            {
                ourReason = e.what();
                const std::string prefix = "fsi::comm: ";
                if (ourReason.rfind(prefix, 0) == 0)
                    ourReason.erase(0, prefix.size());
            }
            Message verdict;
            verdict.kind = MessageKind::HelloReply;
            verdict.integers = {ourReason.empty() ? 1 : 0};
            verdict.text = ourReason;
            sendRaw(interComm_, verdict, self_.protocolVersion, timeout, peerName());
            try
            {
                const Message reply =
                    receiveRaw(interComm_, self_.protocolVersion, timeout,
                               "waiting for the handshake verdict from " + peerName());
                if (reply.kind != MessageKind::HelloReply || reply.integers.size() != 1)
                    throw ProtocolError("fsi::comm: expected HelloReply from the peer, got " +
                                        toString(reply.kind));
                if (reply.integers[0] != 1)
                    peerReason = reply.text;
            }
            catch (const ProtocolError& e)
            {
                if (ourReason.empty())
                    throw;
            }
            if (!ourReason.empty())
                throw ProtocolError("fsi::comm: handshake of " + self_.program + " with " +
                                    peerName() + " failed: " + ourReason);
            if (!peerReason.empty())
                throw ProtocolError("fsi::comm: handshake failed: " + peerName() + " rejected " +
                                    self_.program + ": " + peerReason);
            std::vector<char> bytes;
            put64(bytes, static_cast<std::int64_t>(peer_.role));
            put64(bytes, peer_.ranks);
            put64(bytes, static_cast<std::int64_t>(peer_.interfaceSizes.size()));
            for (const auto size : peer_.interfaceSizes)
                put64(bytes, size);
            bytes.insert(bytes.end(), peer_.program.begin(), peer_.program.end());
            return bytes;
        },
        nonRootBound(timeout), timeout, "handshake");
    throwIfFailed(shaken, localRank_, peerName());
    const std::vector<char>& bytes = shaken.bytes;
    if (!isRoot())
    {
        std::size_t at = 0;
        peer_.role = static_cast<Role>(get64(bytes, at));
        peer_.ranks = static_cast<int>(get64(bytes, at));
        peer_.interfaceSizes.resize(static_cast<std::size_t>(get64(bytes, at)));
        for (auto& size : peer_.interfaceSizes)
            size = get64(bytes, at);
        peer_.program.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end());
        peerKnown_ = true;
    }
}

void Channel::send(const Message& message)
{
    if (!isRoot())
        return;
    if (closed_ || !healthy_)
        throw CommError("fsi::comm: send on a closed or failed channel", false, localRank_);
    try
    {
        sendRaw(interComm_, message, self_.protocolVersion, options_.timeoutSeconds, peerName());
    }
    catch (...)
    {
        fail();
        throw;
    }
}

void Channel::send(MessageKind kind, std::int64_t timeStep, std::int64_t iteration,
                   std::vector<double> values)
{
    Message message;
    message.kind = kind;
    message.timeStep = timeStep;
    message.iteration = iteration;
    message.values = std::move(values);
    send(message);
}

Message Channel::receive(MessageKind expected)
{
    return receiveOnRoot(expected, false, options_.timeoutSeconds);
}

Message Channel::receiveAny()
{
    return receiveOnRoot(MessageKind::Finish, true, options_.timeoutSeconds);
}

Message Channel::receiveOnRoot(MessageKind expected, bool anyKind, double timeout)
{
    if (closed_ || !healthy_)
        throw CommError("fsi::comm: receive on a closed or failed channel", false, localRank_);
    Message message;
    const std::vector<char> bytes = shareRootOutcome(
        "receive", timeout,
        [&]
        {
            const std::string what = "waiting for " +
                                     (anyKind ? std::string("a message") : toString(expected)) +
                                     " from " + peerName();
            message = receiveRaw(interComm_, self_.protocolVersion, timeout, what);
            if (message.kind == MessageKind::Abort)
            {
                peerKnowsWeStop_ = true;
                throw PeerAbortError(peerName(), message.text, true, 0);
            }
            if (!anyKind && message.kind != expected)
            {
                throw ProtocolError("fsi::comm: expected " + toString(expected) + " from " +
                                    peerName() + ", received " + toString(message.kind) +
                                    " (step " + std::to_string(message.timeStep) + ", iteration " +
                                    std::to_string(message.iteration) + ")");
            }
            Message small = message;
            small.values.clear();
            std::vector<char> header;
            for (const auto w : encodeHeader(headerOf(small)))
                put64(header, w);
            put64(header, message.valueCount);
            const std::vector<char> payload = encodePayload(small);
            header.insert(header.end(), payload.begin(), payload.end());
            return header;
        });
    if (!isRoot())
    {
        std::size_t at = 0;
        EncodedHeader words{};
        for (auto& w : words)
            w = get64(bytes, at);
        const std::int64_t valueCount = get64(bytes, at);
        const MessageHeader header = decodeHeader(words, kProtocolVersion);
        decodePayload(
            header, std::vector<char>(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end()),
            message);
        message.valueCount = valueCount;
    }
    return message;
}

void Channel::sendAbort(const std::string& reason) noexcept
{
    peerKnowsWeStop_ = true;
    if (!isRoot() || closed_ || interComm_ == MPI_COMM_NULL)
        return;
    try
    {
        Message abort;
        abort.kind = MessageKind::Abort;
        abort.text = reason;
        sendRaw(interComm_, abort, self_.protocolVersion, std::min(options_.timeoutSeconds, 5.0),
                peerName());
    }
    catch (...)
    {
        fail();
    }
}

void Channel::close()
{
    if (closed_)
        return;
    {
        detail::Watchdog guard(options_.timeoutSeconds,
                               isRoot() ? "fsi::comm: closing the coupling with " + peerName() +
                                              " did not complete within " +
                                              seconds(options_.timeoutSeconds)
                                        : std::string(),
                               kExitCommTimeout);
        if (interComm_ != MPI_COMM_NULL)
        {
            if (options_.mode == LaunchMode::Port)
                checkMpi(MPI_Comm_disconnect(&interComm_), "MPI_Comm_disconnect");
            else
                checkMpi(MPI_Comm_free(&interComm_), "MPI_Comm_free");
        }
        if (localComm_ != MPI_COMM_NULL)
            checkMpi(MPI_Comm_free(&localComm_), "MPI_Comm_free");
    }
    closed_ = true;
}

void Channel::requireOpen(const char* operation) const
{
    if (closed_ || !healthy_)
        throw CommError(std::string("fsi::comm: ") + operation + " on a closed or failed channel",
                        false, localRank_);
}

void Channel::onRootShared(const std::string& what, const std::function<void()>& work)
{
    shareRootOutcome(what, options_.timeoutSeconds,
                     [&]
                     {
                         work();
                         return std::vector<char>();
                     });
}

std::vector<char> Channel::shareRootOutcome(const std::string& what, double timeout,
                                            const std::function<std::vector<char>()>& work)
{
    RootOutcome outcome;
    try
    {
        outcome = runOnRootAndShare(localComm_, localSize_, isRoot(), work, nonRootBound(timeout),
                                    timeout, what);
    }
    catch (...)
    {
        fail();
        throw;
    }
    if (outcome.status != kOk)
    {
        // After a protocol error the message stream is still in step: the channel stays usable
        // for sending Abort. A timeout or an MPI error leaves requests pending: unusable.
        if (outcome.status == kPeerAbort)
            peerKnowsWeStop_ = true;
        else if (outcome.status != kProtocol)
            fail();
        throwIfFailed(outcome, localRank_, peerName());
    }
    return std::move(outcome.bytes);
}

void Channel::sendRowMaps(const std::vector<std::vector<std::int64_t>>& rowsOfEachArray)
{
    requireOpen("sendRowMaps");
    std::vector<std::int64_t> words{static_cast<std::int64_t>(rowsOfEachArray.size())};
    for (const auto& rows : rowsOfEachArray)
        words.push_back(static_cast<std::int64_t>(rows.size()));
    for (const auto& rows : rowsOfEachArray)
        words.insert(words.end(), rows.begin(), rows.end());
    const std::string what =
        "sending the interface rows of rank " + std::to_string(localRank_) + " to " + peerName();
    try
    {
        MPI_Request request = MPI_REQUEST_NULL;
        checkMpi(MPI_Isend(words.data(), messageCount(words.size(), what), MPI_INT64_T, 0,
                           kTagRowMap, interComm_, &request),
                 what);
        waitForPeer(request, options_.timeoutSeconds, what, localRank_, Transfer::Send);
    }
    catch (...)
    {
        fail();
        throw;
    }
}

std::vector<RowMap> Channel::receiveRowMaps(const std::vector<RowShape>& shapes)
{
    requireOpen("receiveRowMaps");
    std::vector<RowMap> maps(shapes.size());
    for (std::size_t a = 0; a < shapes.size(); ++a)
    {
        maps[a].rows = shapes[a].rows;
        maps[a].width = shapes[a].width;
    }
    onRootShared(
        "receiving the interface rows of " + peerName(),
        [&]
        {
            const auto peerRank = [this](int r)
            { return peerName() + " rank " + std::to_string(r); };
            for (int r = 0; r < peer_.ranks; ++r)
            {
                const std::vector<std::int64_t> words = receiveSized<std::int64_t>(
                    interComm_, r, kTagRowMap, MPI_INT64_T, options_.timeoutSeconds,
                    "waiting for the interface rows of " + peerRank(r), 0);
                const auto arrays = static_cast<std::int64_t>(shapes.size());
                if (words.empty() || words[0] != arrays ||
                    static_cast<std::int64_t>(words.size()) < 1 + arrays)
                    throw ProtocolError("fsi::comm: " + peerRank(r) + " announced " +
                                        (words.empty()
                                             ? std::string("nothing")
                                             : std::to_string(words[0]) + " interface arrays") +
                                        ", expected " + std::to_string(arrays));
                std::size_t at = 1 + shapes.size();
                for (std::size_t a = 0; a < shapes.size(); ++a)
                {
                    const auto n = static_cast<std::size_t>(words[1 + a]);
                    if (n > words.size() - at)
                        throw ProtocolError("fsi::comm: " + peerRank(r) +
                                            ": short interface row announcement");
                    std::vector<std::int64_t> rows(words.begin() + static_cast<std::ptrdiff_t>(at),
                                                   words.begin() +
                                                       static_cast<std::ptrdiff_t>(at + n));
                    at += n;
                    for (const std::int64_t row : rows)
                        if (row < 0 || row >= shapes[a].rows)
                            throw ProtocolError("fsi::comm: " + peerRank(r) + " holds row " +
                                                std::to_string(row) + " of interface array " +
                                                std::to_string(a) + ", which has " +
                                                std::to_string(shapes[a].rows) + " rows");
                    maps[a].rowsOfPeerRank.push_back(std::move(rows));
                }
            }
            for (std::size_t a = 0; a < shapes.size(); ++a)
            {
                if (!shapes[a].partition)
                    continue;
                std::vector<int> holders(static_cast<std::size_t>(shapes[a].rows), 0);
                for (const auto& rows : maps[a].rowsOfPeerRank)
                    for (const std::int64_t row : rows)
                        ++holders[static_cast<std::size_t>(row)];
                const auto bad =
                    std::find_if(holders.begin(), holders.end(), [](int n) { return n != 1; });
                if (bad != holders.end())
                    throw ProtocolError("fsi::comm: interface array " + std::to_string(a) + " of " +
                                        peerName() + " is not split into disjoint parts: row " +
                                        std::to_string(bad - holders.begin()) + " is held by " +
                                        std::to_string(*bad) + " ranks");
            }
        });
    return maps;
}

void Channel::scatterRows(const RowMap& map, const std::vector<double>& whole)
{
    requireOpen("scatterRows");
    onRootShared(
        "sending interface rows to " + peerName(),
        [&]
        {
            const auto width = static_cast<std::size_t>(map.width);
            if (whole.size() != static_cast<std::size_t>(map.rows) * width)
                throw CommError("fsi::comm: scatterRows: the array has " +
                                std::to_string(whole.size()) + " values, its map " +
                                std::to_string(map.rows) + " rows of " + std::to_string(width));
            const std::size_t ranks = map.rowsOfPeerRank.size();
            std::vector<std::vector<double>> parts(ranks);
            std::vector<MPI_Request> requests(ranks, MPI_REQUEST_NULL);
            const std::string what = "sending interface rows to " + peerName();
            for (std::size_t r = 0; r < ranks; ++r)
            {
                const auto& rows = map.rowsOfPeerRank[r];
                parts[r].resize(rows.size() * width);
                for (std::size_t k = 0; k < rows.size(); ++k)
                    for (std::size_t c = 0; c < width; ++c)
                        parts[r][k * width + c] =
                            whole[static_cast<std::size_t>(rows[k]) * width + c];
                checkMpi(MPI_Isend(parts[r].data(), messageCount(parts[r].size(), what), MPI_DOUBLE,
                                   static_cast<int>(r), kTagRows, interComm_, &requests[r]),
                         what);
            }
            for (std::size_t r = 0; r < ranks; ++r)
                waitForPeer(requests[r], options_.timeoutSeconds,
                            what + " (rank " + std::to_string(r) + ")", 0, Transfer::Send);
        });
}

std::vector<double> Channel::receiveOwnRows(std::int64_t count)
{
    requireOpen("receiveOwnRows");
    const std::string what = "waiting for the interface rows of rank " +
                             std::to_string(localRank_) + " from " + peerName();
    std::vector<double> own;
    try
    {
        own = receiveSized<double>(interComm_, 0, kTagRows, MPI_DOUBLE, options_.timeoutSeconds,
                                   what, localRank_);
    }
    catch (...)
    {
        fail();
        throw;
    }
    if (static_cast<std::int64_t>(own.size()) != count)
        throw ProtocolError("fsi::comm: rank " + std::to_string(localRank_) + " received " +
                                std::to_string(own.size()) + " interface values from " +
                                peerName() + ", expected " + std::to_string(count),
                            false, localRank_);
    return own;
}

void Channel::sendOwnRows(const std::vector<double>& own)
{
    requireOpen("sendOwnRows");
    const std::string what =
        "sending the interface rows of rank " + std::to_string(localRank_) + " to " + peerName();
    try
    {
        MPI_Request request = MPI_REQUEST_NULL;
        checkMpi(MPI_Isend(own.data(), messageCount(own.size(), what), MPI_DOUBLE, 0, kTagRows,
                           interComm_, &request),
                 what);
        waitForPeer(request, options_.timeoutSeconds, what, localRank_, Transfer::Send);
    }
    catch (...)
    {
        fail();
        throw;
    }
}

std::vector<double> Channel::gatherRows(const RowMap& map)
{
    requireOpen("gatherRows");
    std::vector<double> whole;
    onRootShared(
        "receiving interface rows from " + peerName(),
        [&]
        {
            const auto width = static_cast<std::size_t>(map.width);
            const std::size_t ranks = map.rowsOfPeerRank.size();
            std::vector<std::vector<double>> parts(ranks);
            std::vector<MPI_Request> requests(ranks, MPI_REQUEST_NULL);
            const std::string what = "waiting for interface rows from " + peerName();
            for (std::size_t r = 0; r < ranks; ++r)
            {
                parts[r].resize(map.rowsOfPeerRank[r].size() * width);
                checkMpi(MPI_Irecv(parts[r].data(), messageCount(parts[r].size(), what), MPI_DOUBLE,
                                   static_cast<int>(r), kTagRows, interComm_, &requests[r]),
                         what);
            }
            // every transfer completes before a count is judged: no request is left pending
            std::vector<int> counts(ranks, 0);
            for (std::size_t r = 0; r < ranks; ++r)
            {
                MPI_Status status;
                waitForPeer(requests[r], options_.timeoutSeconds,
                            what + " (rank " + std::to_string(r) + ")", 0, Transfer::Receive,
                            &status);
                checkMpi(MPI_Get_count(&status, MPI_DOUBLE, &counts[r]), what);
            }
            whole.assign(static_cast<std::size_t>(map.rows) * width, 0.0);
            for (std::size_t r = 0; r < ranks; ++r)
            {
                const int count = counts[r];
                if (static_cast<std::size_t>(count) != parts[r].size())
                    throw ProtocolError("fsi::comm: " + peerName() + " rank " + std::to_string(r) +
                                        " sent " + std::to_string(count) + " interface values, " +
                                        "expected " + std::to_string(parts[r].size()));
                const auto& rows = map.rowsOfPeerRank[r];
                for (std::size_t k = 0; k < rows.size(); ++k)
                    for (std::size_t c = 0; c < width; ++c)
                        whole[static_cast<std::size_t>(rows[k]) * width + c] =
                            parts[r][k * width + c];
            }
        });
    return whole;
}

std::vector<double> Channel::gatherToRoot(const std::vector<double>& local) const
{
    return fsi::comm::gatherToRoot(localComm_, local, options_.timeoutSeconds);
}

std::vector<double> Channel::scatterFromRoot(const std::vector<double>& rootValues,
                                             std::int64_t localCount) const
{
    return fsi::comm::scatterFromRoot(localComm_, rootValues, localCount, options_.timeoutSeconds);
}

void Channel::broadcastFromRoot(std::vector<double>& values) const
{
    fsi::comm::broadcastFromRoot(localComm_, values, options_.timeoutSeconds);
}

} // namespace fsi::comm
