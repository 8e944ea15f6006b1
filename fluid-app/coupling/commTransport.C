// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the coupled transport over fsi::comm (compiled as C++17, no
// OpenFOAM headers). The messages and their payloads are those of
// fsi/comm/Protocol.hpp (the one description of the wire format, shared with
// solid-app): Channel::open (Hello: role fluid, program "fluid-app", interface
// sizes {nPoints, nFaces}) -> InterfaceGeometry -> each rank's row maps; then
// Solve (+ each rank's displacements) -> Forces (+ each rank's forces), Accept,
// and Finish (close, exit 0) or Abort (exit non-zero with the peer's reason).
#include "couplingTransport.H"

#ifdef FSI_FLUID_WITH_COMM

#include "fsi/comm/Channel.hpp"
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/comm/Protocol.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace fsi::fluid
{
namespace
{

std::optional<comm::LaunchOptions> launchOptions;

class CommTransport : public CouplingTransport
{
public:
    explicit CommTransport(const comm::LaunchOptions& options) : options_(options) {}

    void handshake(const InterfaceGeometry& geometry, long nPoints, long nFaces,
                   const LocalInterface& local) override
    {
        guard([&] {
            comm::Identity self;
            self.role = comm::Role::Fluid;
            self.program = "fluid-app";
            self.interfaceSizes = {nPoints, nFaces};
            channel_.emplace(comm::Channel::open(options_, self));
            comm::protocol::InterfaceGeometry g;
            if (channel_->isRoot())
                g = {geometry.pointCoordinates, geometry.faceCentres, geometry.faceAreaVectors};
            const comm::Message m = comm::protocol::encode(g);
            channel_->send(m);
            std::vector<std::vector<std::int64_t>> rows(2);
            rows[comm::protocol::kPointRows].assign(local.pointRows.begin(),
                                                    local.pointRows.end());
            rows[comm::protocol::kFaceRows].assign(local.faceRows.begin(), local.faceRows.end());
            channel_->sendRowMaps(rows);
            localPoints_ = static_cast<std::int64_t>(local.pointRows.size());
        });
    }

    Command receive() override
    {
        Command c;
        guard([&] {
            comm::Message m = channel_->receiveAny();
            c.step = static_cast<int>(m.timeStep);
            c.iteration = static_cast<int>(m.iteration);
            switch (m.kind)
            {
            case comm::MessageKind::Solve:
            {
                const comm::protocol::Solve solve = comm::protocol::decodeSolve(m);
                c.kind = CommandKind::solve;
                c.time = solve.time;
                const auto start = std::chrono::steady_clock::now();
                c.displacements =
                    channel_->receiveOwnRows(comm::protocol::kRowWidth * localPoints_);
                c.exchangeSeconds = std::chrono::duration<double>(
                                        std::chrono::steady_clock::now() - start)
                                        .count();
                c.accuracyGiven = solve.accuracyGiven;
                c.forceTolerance = solve.forceTolerance;
                c.residualDrop = solve.residualDrop;
                c.minIterations = static_cast<int>(solve.minIterations);
                break;
            }
            case comm::MessageKind::Accept:
                c.kind = CommandKind::accept;
                c.time = comm::protocol::decodeAccept(m).time;
                break;
            case comm::MessageKind::Finish:
                c.kind = CommandKind::finish;
                channel_->close();
                break;
            default:
                throw comm::ProtocolError("fluid-app: unexpected " + comm::toString(m.kind) +
                                              " from " + channel_->peerName() +
                                              " (expected Solve, Accept or Finish)",
                                          true, channel_->localRank());
            }
        });
        return c;
    }

    void sendForces(const Command& solve, const ForceReport& report) override
    {
        guard([&] {
            comm::protocol::Forces f;
            f.level = solve.step;
            f.iteration = solve.iteration;
            f.iterations = report.simpleIterations;
            f.converged = report.converged;
            f.residuals = report.residuals;
            f.band = report.band;
            channel_->send(comm::protocol::encode(f));
            channel_->sendOwnRows(report.faceForces);
        });
    }

    void abortRun(const std::string& reason) override
    {
        const std::runtime_error error("fluid-app: " + reason);
        comm::exitOnError(error, channel_ ? &*channel_ : nullptr, comm::ErrorScope::AllRanks);
    }

    std::string describe() const override
    {
        std::ostringstream os;
        os << "fsi::comm, launch " << comm::toString(options_.mode);
        if (options_.mode == comm::LaunchMode::Port)
            os << ", port file " << options_.portFile;
        os << ", timeout " << options_.timeoutSeconds << " s";
        if (channel_)
            os << ", peer " << channel_->peerName();
        return os.str();
    }

private:
    // Every comm error ends the run through the comm layer's exit path
    // (Abort to the peer, or MPI_Abort after a timeout).
    template <class F> void guard(F&& f)
    {
        try
        {
            f();
        }
        catch (const std::exception& e)
        {
            comm::exitOnError(e, channel_ ? &*channel_ : nullptr);
        }
    }

    comm::LaunchOptions options_;
    std::optional<comm::Channel> channel_;
    std::int64_t localPoints_ = 0; // this rank's interface points
};

bool hasFlag(int argc, char** argv, const char* flag)
{
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], flag) == 0)
            return true;
    return false;
}

// The options fsi::comm takes out of the command line before OpenFOAM reads it (so they are
// not in OpenFOAM's -help table): printed ahead of OpenFOAM's usage.
const char* const commHelp =
    "\nfluid-app coupling options (fsi::comm; GNU style, before or after OpenFOAM's):\n"
    "  --launch port|mpmd      how to meet solid-app: one mpirun A : B (mpmd, default) or the\n"
    "                          MPI port solid-app publishes in a file (port)\n"
    "  --port-file PATH        port mode: the file with solid-app's port name\n"
    "                          (default fsi-comm.port)\n"
    "  --comm-timeout SECONDS  bound of every wait on solid-app (default 600)\n"
    "Run modes (system/fsiDict mode, or the options -coupled / -rigid / -prescribed below);\n"
    "-restart continues a coupled run together with solid-app --restart.\n\n";

} // namespace

void initialiseComm(int& argc, char**& argv, RunMode mode)
{
    try
    {
        // No coupling (and no MPI start here) for the uncoupled modes and OpenFOAM's help.
        const bool uncoupled = mode != RunMode::coupled;
        const bool help = hasFlag(argc, argv, "-help") || hasFlag(argc, argv, "-help-full");
        if (uncoupled || help || hasFlag(argc, argv, "-doc") || hasFlag(argc, argv, "-srcDoc"))
        {
            launchOptions = comm::parseLaunchOptions(argc, argv); // strip the flags only
            if (help) // OpenFOAM's usage (its own options) follows and exits 0
                std::printf("%s", commHelp);
            return;
        }
        launchOptions = comm::initialiseMpmdWorld(argc, argv);
    }
    catch (const std::exception& e)
    {
        comm::exitOnError(e, nullptr, comm::ErrorScope::AllRanks);
    }
}

bool commAvailable() { return true; }

std::unique_ptr<CouplingTransport> makeCommTransport()
{
    if (!launchOptions)
        throw std::runtime_error("fluid-app: initialiseComm was not called first in main");
    return std::make_unique<CommTransport>(*launchOptions);
}

} // namespace fsi::fluid

#else // built without comm/

namespace fsi
{
namespace fluid
{
void initialiseComm(int&, char**&, RunMode) {}
bool commAvailable() { return false; }
std::unique_ptr<CouplingTransport> makeCommTransport() { return nullptr; }
} // namespace fluid
} // namespace fsi

#endif
