// SPDX-License-Identifier: GPL-3.0-or-later
// The exchange the comm test drivers (fluid_like, solid_like) play, with exact value checks.
// Both drivers include this header; all values are computed by formulas on both sides and
// compared bit for bit after the transfer.
#pragma once

#include "fsi/comm/Channel.hpp"
#include "fsi/comm/MpmdWorld.hpp"

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace fsi::comm::test
{

// Array sizes exchanged per time level (one Solve/Forces round each).
inline const std::vector<std::int64_t> kSizes = {0, 1, 1000, 100000};

inline double displacementValue(std::int64_t i, std::int64_t step, std::int64_t iteration)
{
    return static_cast<double>(i % 97 - 48) * 1.0e-4 + static_cast<double>(step) * 0.5 +
           static_cast<double>(iteration) * 1.0e-9;
}
inline double forceValue(double displacement, std::int64_t i)
{
    return -3.0 * displacement + static_cast<double>(i) * 0.25;
}
inline double geometryValue(std::int64_t i)
{
    return static_cast<double>(i) * 1.5e-3 - 7.0;
}

// Block partition of n values over size ranks: count of rank r, and its first global index.
inline std::int64_t blockCount(std::int64_t n, int size, int rank)
{
    return n / size + (rank < n % size ? 1 : 0);
}
inline std::int64_t blockStart(std::int64_t n, int size, int rank)
{
    return rank * (n / size) + std::min<std::int64_t>(rank, n % size);
}

// The distributed interface arrays of the exchange (Channel row maps), two per size n of kSizes
// (array 2k: "points", 2k + 1: "faces"; n rows of 3 values each). Rank r of S holds the rows
// i = r (mod S): faces in descending order (a partition), points ascending plus every 7th row of
// the previous rank (shared rows, like points on processor boundaries; on one rank: held twice).
inline std::vector<std::int64_t> pointRowsOf(std::int64_t n, int size, int rank)
{
    std::vector<std::int64_t> rows;
    for (std::int64_t i = 0; i < n; ++i)
        if (i % size == rank || ((i + 1) % size == rank && i % 7 == 0))
            rows.push_back(i);
    return rows;
}
inline std::vector<std::int64_t> faceRowsOf(std::int64_t n, int size, int rank)
{
    std::vector<std::int64_t> rows;
    for (std::int64_t i = n - 1; i >= 0; --i)
        if (i % size == rank)
            rows.push_back(i);
    return rows;
}
inline std::vector<std::vector<std::int64_t>> rowMapsOf(int size, int rank)
{
    std::vector<std::vector<std::int64_t>> maps;
    for (const std::int64_t n : kSizes)
    {
        maps.push_back(pointRowsOf(n, size, rank));
        maps.push_back(faceRowsOf(n, size, rank));
    }
    return maps;
}
// Value c of row `row` of a distributed array.
inline double rowDisplacement(std::int64_t row, int c, std::int64_t step, std::int64_t iteration)
{
    return displacementValue(3 * row + c, step, iteration);
}
inline double rowForce(std::int64_t row, int c, std::int64_t step, std::int64_t iteration)
{
    return forceValue(rowDisplacement(row, c, step, iteration), 3 * row + c);
}

struct DriverFlags
{
    std::int64_t geometrySize = 12;            // InterfaceGeometry values sent by the fluid
    int protocolVersion = kProtocolVersion;    // --protocol-version (tests a mismatch)
    int expectPeerRanks = 0;                   // --expect-peer-ranks
    std::vector<std::int64_t> expectPeerSizes; // --expect-peer-sizes a,b
    std::vector<std::int64_t> interfaceSizes;  // --interface-sizes a,b (announced)
    int dieAfter = -1;        // --die-after N: _exit(3) before the N-th channel operation
    bool dieBySignal = false; // --die-signal: raise SIGKILL instead of _exit(3)
    int quitAfter = -1;       // --quit-after N: MPI_Finalize and exit(0) before the N-th operation
    int abortAfter = -1;      // --abort-after N: send Abort instead of the N-th operation
    int wrongKindAt = -1;     // --send-wrong-kind-at N: the N-th operation sends Accept instead
    bool handshakeOnly = false;                   // --handshake-only: solid sends Finish right away
    std::string expectPeerProgram = "fluid-like"; // --expect-peer-program (solid side)
    int checkWorldSize = 0; // --check-world-size N (fluid with redirect): MPI_COMM_WORLD size
    int pauseBefore = -1;   // --pause-before N S: sleep S seconds before the N-th operation
    double pauseSeconds = 0.0;
    int dieBeforeRows = -1;       // --die-before-rows N (solid): _exit(3) after the N-th Solve
                                  // header, before its rows are sent
    bool overlapFaceRows = false; // --overlap-face-rows (fluid): the last rank also holds face
                                  // row 0 of array 5 (a map that is not a partition)
};

inline std::vector<std::int64_t> parseList(const std::string& text)
{
    std::vector<std::int64_t> out;
    std::size_t at = 0;
    while (at <= text.size() && !text.empty())
    {
        const std::size_t comma = text.find(',', at);
        out.push_back(std::stoll(text.substr(at, comma - at)));
        if (comma == std::string::npos)
            break;
        at = comma + 1;
    }
    return out;
}

inline DriverFlags parseDriverFlags(int argc, char** argv)
{
    DriverFlags f;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto next = [&]() -> std::string
        {
            if (i + 1 >= argc)
                throw std::runtime_error(a + ": missing value");
            return argv[++i];
        };
        if (a == "--protocol-version")
            f.protocolVersion = std::stoi(next());
        else if (a == "--expect-peer-ranks")
            f.expectPeerRanks = std::stoi(next());
        else if (a == "--expect-peer-sizes")
            f.expectPeerSizes = parseList(next());
        else if (a == "--interface-sizes")
            f.interfaceSizes = parseList(next());
        else if (a == "--die-after")
            f.dieAfter = std::stoi(next());
        else if (a == "--quit-after")
            f.quitAfter = std::stoi(next());
        else if (a == "--die-signal")
            f.dieBySignal = true;
        else if (a == "--abort-after")
            f.abortAfter = std::stoi(next());
        else if (a == "--send-wrong-kind-at")
            f.wrongKindAt = std::stoi(next());
        else if (a == "--handshake-only")
            f.handshakeOnly = true;
        else if (a == "--expect-peer-program")
            f.expectPeerProgram = next();
        else if (a == "--check-world-size")
            f.checkWorldSize = std::stoi(next());
        else if (a == "--die-before-rows")
            f.dieBeforeRows = std::stoi(next());
        else if (a == "--overlap-face-rows")
            f.overlapFaceRows = true;
        else if (a == "--pause-before")
        {
            f.pauseBefore = std::stoi(next());
            f.pauseSeconds = std::stod(next());
        }
        else
            throw std::runtime_error("unknown argument '" + a + "'");
    }
    return f;
}

// Thrown by --abort-after on every rank at the same point (an error of the whole program).
struct CollectiveTestError : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

// Counts channel operations and injects the requested failure before the N-th one.
class FaultInjector
{
public:
    FaultInjector(const DriverFlags& flags, Channel& channel) : flags_(flags), channel_(channel) {}
    // Returns true when this operation must send a wrong kind (--send-wrong-kind-at).
    bool before(const char* what)
    {
        ++count_;
        if (count_ == flags_.pauseBefore)
            ::usleep(static_cast<useconds_t>(flags_.pauseSeconds * 1e6));
        if (count_ == flags_.dieAfter)
        {
            std::fprintf(stderr, "%s: test: dying before operation %d (%s)\n",
                         channel_.self().program.c_str(), count_, what);
            std::fflush(stderr);
            if (flags_.dieBySignal)
                std::raise(SIGKILL);
            ::_exit(3);
        }
        if (count_ == flags_.quitAfter)
        {
            std::fprintf(stderr, "%s: test: quitting quietly before operation %d (%s)\n",
                         channel_.self().program.c_str(), count_, what);
            std::fflush(stderr);
            finaliseMpi();
            std::exit(0);
        }
        if (count_ == flags_.abortAfter)
            throw CollectiveTestError("test abort requested before operation " +
                                      std::to_string(count_));
        return count_ == flags_.wrongKindAt;
    }

private:
    const DriverFlags& flags_;
    Channel& channel_;
    int count_ = 0;
};

inline void require(bool ok, const std::string& what)
{
    if (!ok)
        throw std::runtime_error("check failed: " + what);
}

} // namespace fsi::comm::test
