// SPDX-License-Identifier: GPL-3.0-or-later
// The coupling channel between the fluid and the solid program.
//
// A Channel owns two communicators: localComm() (this program's ranks, a private duplicate)
// and interComm() (intercommunicator to the peer program). Messages travel root to root
// (local rank 0 to peer rank 0); the other ranks of a side take part through bounded local
// broadcasts, so every call below is made by ALL ranks of this program unless noted.
// Every wait is bounded by LaunchOptions::timeoutSeconds; expiry throws TimeoutError naming
// the peer. Not thread safe; MPI must be initialised (initialiseMpi) before open().
#pragma once

#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/Message.hpp"

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fsi
{
namespace comm
{

// One interface array (rows x width values, row-major) held in parts by the ranks of the
// distributed side (the fluid: each rank its own patch points or faces) and whole by the peer's
// root (the solid's driver): which global rows each peer rank holds, in the order its values
// travel. A row may be held by several ranks (points on processor boundaries) unless the map
// is a partition (faces).
struct RowMap
{
    std::int64_t rows = 0;                                 // rows of the whole array
    int width = 3;                                         // values per row
    std::vector<std::vector<std::int64_t>> rowsOfPeerRank; // whole side's root only
};

// What the whole side requires of one array's map (receiveRowMaps checks it).
struct RowShape
{
    std::int64_t rows = 0;
    int width = 3;
    bool partition = false; // every row held by exactly one peer rank (needed by gatherRows)
};

// Solid = driver and port-mode server; Fluid = port-mode client.
enum class Role : std::int32_t
{
    Fluid = 1,
    Solid = 2,
};
std::string toString(Role role); // "fluid" | "solid"

// What this side announces in the handshake.
struct Identity
{
    Role role = Role::Solid;
    std::string program;                      // e.g. "solid-app"; shown in the peer's errors
    std::vector<std::int64_t> interfaceSizes; // e.g. fluid {points, faces}, solid {wetted nodes}
    std::int32_t protocolVersion = kProtocolVersion; // change only to test version mismatches
};

// Checks on the peer's announcement; empty / 0 = not checked. A failed check ends the
// handshake on both sides with ProtocolError (both messages name the mismatch).
struct PeerExpectation
{
    std::string program;
    int ranks = 0;
    std::vector<std::int64_t> interfaceSizes;
};

// What the peer announced.
struct PeerInfo
{
    Role role = Role::Fluid;
    std::string program;
    int ranks = 0;
    std::vector<std::int64_t> interfaceSizes;
};

class Channel
{
public:
    // Collective over this program's ranks (and, in MPMD, with the peer). Port mode: the Solid
    // opens a port, publishes it in options.portFile and accepts; the Fluid waits for the
    // file, rejects a stale or garbage file with CommError, and connects. MPMD: splits
    // MPI_COMM_WORLD by MPI_APPNUM (once per process, see MpmdWorld.hpp) and builds the
    // intercommunicator. Then the handshake: protocol version, roles, program names, rank
    // counts and interface sizes are exchanged and checked against expectation.
    static Channel open(const LaunchOptions& options, const Identity& self,
                        const PeerExpectation& expectation = {});

    Channel(Channel&& other) noexcept;
    Channel& operator=(Channel&& other) = delete;
    Channel(const Channel&) = delete;
    Channel& operator=(const Channel&) = delete;
    // If close() was not called and the channel is healthy, frees the communicators locally
    // (MPI_Comm_free, no talk with the peer); after an error it leaves them alone. Never
    // blocks. Call close() for an orderly end (port mode needs MPI_Comm_disconnect).
    ~Channel();

    // Only the local root's message is transmitted; other ranks return at once (their
    // argument is ignored). Bounded: TimeoutError if the peer does not take the data.
    void send(const Message& message);
    void send(MessageKind kind, std::int64_t timeStep, std::int64_t iteration,
              std::vector<double> values = {});

    // Waits for the next message. The root receives it; kind, step, iteration, scalars,
    // integers, text and valueCount are broadcast to all local ranks; values stay on the root
    // (use scatterFromRoot/broadcastFromRoot to distribute them). The same exception is
    // thrown on every local rank: PeerAbortError on Abort (the peer's reason), ProtocolError
    // if the kind is not the expected one (the channel stays usable to send Abort),
    // TimeoutError after timeoutSeconds (non-root ranks: timeout + max(2 s, 10 %)).
    Message receive(MessageKind expected);
    Message receiveAny();

    // Best effort, bounded by min(timeout, 5 s): the root tells the peer why this side stops.
    // Never throws. Called by exitOnError.
    void sendAbort(const std::string& reason) noexcept;

    // Orderly end after Finish was sent/received: disconnects (port) or frees (MPMD) the
    // intercommunicator, frees localComm. Collective with the peer; bounded by a watchdog.
    void close();

    MPI_Comm localComm() const { return localComm_; }
    MPI_Comm interComm() const { return interComm_; }
    int localRank() const { return localRank_; }
    int localSize() const { return localSize_; }
    bool isRoot() const { return localRank_ == 0; }
    const PeerInfo& peer() const { return peer_; }
    const Identity& self() const { return self_; }
    const LaunchOptions& options() const { return options_; }
    // "solid-app (solid, 2 ranks)" or the role before the handshake.
    std::string peerName() const;

    // ---- Distributed interface arrays (DESIGN.md section 4) -------------------------------
    // Each rank of the distributed side (the fluid) exchanges its own rows directly with the
    // peer's root over the intercommunicator: no gather or scatter through the distributed
    // side's root. Every call is made by ALL ranks of this program; bounded by the timeout like
    // send/receive. On the whole side the root does the transfer and the outcome is shared, so
    // the same exception is thrown on every rank; on the distributed side a rank's failure is
    // its own (TimeoutError, ProtocolError or CommError with everyRank() false).
    //
    // Distributed side, once after open(): this rank's global rows of each array, in the
    // order its values will travel.
    void sendRowMaps(const std::vector<std::vector<std::int64_t>>& rowsOfEachArray);
    // Whole side, once after open(): every peer rank's rows of each array, checked against
    // shapes (one per array: rows in range, a partition where asked; else ProtocolError naming
    // the array index and the peer rank). The maps' rowsOfPeerRank are filled on the root.
    std::vector<RowMap> receiveRowMaps(const std::vector<RowShape>& shapes);
    // Whole side: each peer rank receives its rows of the root's `whole` (map.rows x
    // map.width values; CommError otherwise).
    void scatterRows(const RowMap& map, const std::vector<double>& whole);
    // Distributed side: this rank's rows sent by scatterRows; `count` values expected
    // (ProtocolError when the peer sent a different number).
    std::vector<double> receiveOwnRows(std::int64_t count);
    // Distributed side: this rank's rows (its map's rows x width values) to the peer's root.
    void sendOwnRows(const std::vector<double>& own);
    // Whole side: the whole array on the root (rows x width; {} elsewhere), every row from the
    // peer rank that holds it; ProtocolError when a rank sent a different number of values.
    // map must be a partition.
    std::vector<double> gatherRows(const RowMap& map);

    // Bounded helpers on localComm() (see Collectives.hpp).
    std::vector<double> gatherToRoot(const std::vector<double>& local) const;
    std::vector<double> scatterFromRoot(const std::vector<double>& rootValues,
                                        std::int64_t localCount) const;
    void broadcastFromRoot(std::vector<double>& values) const;

    // Internal state; public only for exitOnError.
    bool healthy() const { return healthy_; }
    bool peerKnowsWeStop() const { return peerKnowsWeStop_; }

private:
    Channel() = default;
    void connectPort();
    void connectMpmd();
    void handshake(const PeerExpectation& expectation);
    Message receiveOnRoot(MessageKind expected, bool anyKind, double seconds);
    void fail(); // marks the channel unusable
    // Runs work on the root; the outcome (ok or the error's kind and text) reaches every local
    // rank, which then all return or all throw. Bounded.
    void onRootShared(const std::string& what, const std::function<void()>& work);
    // The same for work that returns bytes the other ranks need: every rank returns the root's
    // bytes. An error fails the channel unless it is a protocol error or the peer's Abort.
    std::vector<char> shareRootOutcome(const std::string& what, double timeout,
                                       const std::function<std::vector<char>()>& work);
    void requireOpen(const char* operation) const;

    LaunchOptions options_;
    Identity self_;
    PeerInfo peer_;
    bool peerKnown_ = false;
    MPI_Comm localComm_ = MPI_COMM_NULL;
    MPI_Comm interComm_ = MPI_COMM_NULL;
    int localRank_ = 0;
    int localSize_ = 1;
    bool healthy_ = true;
    bool closed_ = false;
    bool peerKnowsWeStop_ = false;
};

} // namespace comm
} // namespace fsi
