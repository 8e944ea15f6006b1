// SPDX-License-Identifier: GPL-3.0-or-later
// fake_solid: a stand-in driver for fluid-app tests. Plays the solid side of the protocol
// with a prescribed rigid rotation of the fluid's interface points about the z axis.
//
// usage: fake_solid --launch port|mpmd [--port-file F] [--comm-timeout S]
//                   [--angle DEG] [--origin X,Y] [--steps N] [--iterations K]
//                   [--out CSV] [--abort-at-step S] [--expect-fluid-ranks R]
//                   [--die-at-step S [--die-signal N]]
// Per step s = 1..N and iteration k = 1..K it sends Solve(displacement of a rotation by
// s/N * DEG), checks the Forces reply (fsi/comm/Protocol.hpp, 2 residuals), then sends
// Accept(s, time = 10 s) and finally Finish. --abort-at-step sends Abort instead of the
// first Solve of that step. --die-at-step sends the first Solve of that step and then raises
// signal N (default 9, SIGKILL) while the fluid solves. Writes one CSV row per Forces reply
// and prints a summary line.
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/comm/Protocol.hpp"

#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fsi::comm;

namespace
{
struct Flags
{
    double angleDeg = 2.0;
    double origin[2] = {0.2, 0.2};
    int steps = 1;
    int iterations = 2;
    std::string out;
    int abortAtStep = 0;
    int expectFluidRanks = 0;
    int dieAtStep = 0;
    int dieSignal = 9;
};

Flags parse(int argc, char** argv)
{
    Flags f;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto next = [&]() -> std::string
        {
            if (i + 1 >= argc)
                throw std::runtime_error("fake_solid: " + a + " needs a value");
            return argv[++i];
        };
        if (a == "--angle")
            f.angleDeg = std::stod(next());
        else if (a == "--origin")
        {
            const std::string v = next();
            const auto c = v.find(',');
            f.origin[0] = std::stod(v.substr(0, c));
            f.origin[1] = std::stod(v.substr(c + 1));
        }
        else if (a == "--steps")
            f.steps = std::stoi(next());
        else if (a == "--iterations")
            f.iterations = std::stoi(next());
        else if (a == "--out")
            f.out = next();
        else if (a == "--abort-at-step")
            f.abortAtStep = std::stoi(next());
        else if (a == "--expect-fluid-ranks")
            f.expectFluidRanks = std::stoi(next());
        else if (a == "--die-at-step")
            f.dieAtStep = std::stoi(next());
        else if (a == "--die-signal")
            f.dieSignal = std::stoi(next());
        else
            throw std::runtime_error("fake_solid: unknown argument " + a);
    }
    return f;
}

void require(bool ok, const std::string& what)
{
    if (!ok)
        throw std::runtime_error("fake_solid: check failed: " + what);
}
} // namespace

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        initialiseMpi(argc, argv);
        const LaunchOptions launch = parseLaunchOptions(argc, argv);
        const Flags flags = parse(argc, argv);
        PeerExpectation expect;
        expect.program = "fluid-app";
        expect.ranks = flags.expectFluidRanks;
        channel.emplace(Channel::open(launch, {Role::Solid, "fake-solid", {0}}, expect));
        const std::int64_t nPoints = channel->peer().interfaceSizes.at(0);
        const std::int64_t nFaces = channel->peer().interfaceSizes.at(1);
        const protocol::InterfaceGeometry geometry = protocol::decodeGeometry(
            channel->receive(MessageKind::InterfaceGeometry), nPoints, nFaces);
        const bool root = channel->isRoot();
        const std::vector<RowMap> rows = channel->receiveRowMaps(
            {{nPoints, protocol::kRowWidth, false}, {nFaces, protocol::kRowWidth, true}});

        std::ofstream csv;
        if (root && !flags.out.empty())
        {
            csv.open(flags.out);
            csv.precision(17);
            csv << "step,iteration,fluidIterations,residualU,residualP,Fx,Fy,Fz\n";
        }
        const double pi = std::acos(-1.0);
        for (int s = 1; s <= flags.steps; ++s)
        {
            for (int k = 1; k <= flags.iterations; ++k)
            {
                if (s == flags.abortAtStep)
                {
                    // Sends Abort(reason) to the fluid, closes, finalises, exits 1.
                    exitOnError(
                        std::runtime_error("fake-solid: test abort at step " + std::to_string(s)),
                        &*channel, ErrorScope::AllRanks);
                }
                std::vector<double> d;
                if (root)
                {
                    const double t = flags.angleDeg * pi / 180.0 * s / flags.steps;
                    d.assign(3 * nPoints, 0.0);
                    for (std::int64_t i = 0; i < nPoints; ++i)
                    {
                        const double rx = geometry.points[3 * i] - flags.origin[0];
                        const double ry = geometry.points[3 * i + 1] - flags.origin[1];
                        d[3 * i] = std::cos(t) * rx - std::sin(t) * ry - rx;
                        d[3 * i + 1] = std::sin(t) * rx + std::cos(t) * ry - ry;
                    }
                }
                protocol::Solve solve;
                solve.level = s;
                solve.iteration = k;
                solve.time = 10.0 * s;
                channel->send(protocol::encode(solve));
                channel->scatterRows(rows[protocol::kPointRows], d);
                if (s == flags.dieAtStep)
                {
                    std::printf("fake-solid: test: raising signal %d after Solve of step %d\n",
                                flags.dieSignal, s);
                    std::fflush(stdout);
                    std::raise(flags.dieSignal);
                }
                const protocol::Forces f =
                    protocol::decodeForces(channel->receive(MessageKind::Forces), s, k);
                const std::vector<double> faceForces =
                    channel->gatherRows(rows[protocol::kFaceRows]);
                require(f.residuals.size() == 2, "Forces residuals {U, p}");
                if (root)
                {
                    double F[3] = {0, 0, 0};
                    for (std::int64_t i = 0; i < nFaces; ++i)
                        for (int c = 0; c < 3; ++c)
                            F[c] += faceForces[3 * i + c];
                    std::printf("fake-solid: step %d iteration %d: fluid iterations %lld, "
                                "residuals %.3e %.3e, force (%.10g %.10g %.10g) N\n",
                                s, k, static_cast<long long>(f.iterations), f.residuals[0],
                                f.residuals[1], F[0], F[1], F[2]);
                    if (csv)
                        csv << s << ',' << k << ',' << f.iterations << ',' << f.residuals[0] << ','
                            << f.residuals[1] << ',' << F[0] << ',' << F[1] << ',' << F[2] << '\n';
                }
            }
            channel->send(protocol::encode(protocol::Accept{s, 10.0 * s}));
        }
        channel->send(MessageKind::Finish, flags.steps, 0);
        channel->close();
        if (root)
            std::printf("fake-solid: done with %s\n", channel->peerName().c_str());
        channel.reset();
        finaliseMpi();
        return 0;
    }
    catch (const std::exception& e)
    {
        exitOnError(e, channel ? &*channel : nullptr);
    }
}
