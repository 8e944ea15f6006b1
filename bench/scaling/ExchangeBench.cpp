// SPDX-License-Identifier: GPL-3.0-or-later
// exchange-bench: the interface exchange of one coupling iteration (displacements solid ->
// fluid ranks, forces fluid ranks -> solid) over fsi::comm, without any solver, for growing
// interface sizes, in two architectures measured in one invocation:
//   root  the fluid's root relays: the solid root sends the whole array to the fluid root,
//         which cuts it for its ranks (scatterFromRoot), and the forces come back through a
//         gather to the fluid root (gatherToRoot) and one message (protocol version 2);
//   rows  every fluid rank exchanges its own rows with the solid root (Channel::scatterRows /
//         gatherRows; protocol version 3, what solid-app and fluid-app do).
// Figures only, nothing asserted (bench/scaling/README.md).
//
// usage: mpirun -np R exchange-bench --side fluid --launch mpmd
//               : -np 1 exchange-bench --side solid --launch mpmd [--points 10000,100000,1000000]
//                 [--repeats 7]
// The fluid ranks hold contiguous blocks of the points and faces (points also the first point
// of the next block, as processor-boundary points). The solid root prints one line per
// architecture and size:
//   exchange-bench: mode=M points=P fluid_ranks=R repeats=N min_ms=X median_ms=X
//                   us_per_point=X cpu_ms=X
// (us_per_point from the median; cpu_ms: the solid root's CPU time per exchange, median).
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/timing/Clock.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fsi::comm;

namespace
{
struct Flags
{
    std::string side;
    std::vector<std::int64_t> points = {10000, 100000, 1000000};
    int repeats = 7;
};

Flags parse(int argc, char** argv)
{
    Flags f;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string
        {
            if (i + 1 >= argc)
                throw std::runtime_error("exchange-bench: " + a + " needs a value");
            return argv[++i];
        };
        if (a == "--side")
            f.side = next();
        else if (a == "--repeats")
            f.repeats = std::stoi(next());
        else if (a == "--points")
        {
            f.points.clear();
            std::string list = next();
            for (std::size_t at = 0; at <= list.size();)
            {
                const std::size_t comma = std::min(list.find(',', at), list.size());
                f.points.push_back(std::stoll(list.substr(at, comma - at)));
                at = comma + 1;
            }
        }
        else
            throw std::runtime_error("exchange-bench: unknown argument '" + a +
                                     "' (--side fluid|solid, --points LIST, --repeats N)");
    }
    if (f.side != "fluid" && f.side != "solid")
        throw std::runtime_error("exchange-bench: --side fluid|solid is required");
    if (f.repeats < 1)
        throw std::runtime_error("exchange-bench: --repeats must be >= 1");
    return f;
}

std::int64_t blockStart(std::int64_t n, int size, int rank)
{
    return rank * (n / size) + std::min<std::int64_t>(rank, n % size);
}

// Rank r's faces: its block; its points: its block and the first point of the next block.
std::vector<std::int64_t> faceRows(std::int64_t n, int size, int rank)
{
    std::vector<std::int64_t> rows;
    for (std::int64_t i = blockStart(n, size, rank); i < blockStart(n, size, rank + 1); ++i)
        rows.push_back(i);
    return rows;
}
std::vector<std::int64_t> pointRows(std::int64_t n, int size, int rank)
{
    std::vector<std::int64_t> rows = faceRows(n, size, rank);
    if (rank + 1 < size && blockStart(n, size, rank + 1) < n)
        rows.push_back(blockStart(n, size, rank + 1));
    return rows;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// One exchange on the fluid side in architecture `mode`.
void fluidExchange(Channel& channel, const std::string& mode, std::int64_t n,
                   const std::vector<std::int64_t>& points, const std::vector<std::int64_t>& faces)
{
    const int size = channel.localSize();
    std::vector<double> own;
    if (mode == "rows")
    {
        channel.receive(MessageKind::Solve);
        own = channel.receiveOwnRows(3 * static_cast<std::int64_t>(points.size()));
    }
    else
    {
        const Message solve = channel.receive(MessageKind::Solve);
        std::vector<double> packed; // the root cuts the whole array into the ranks' rows
        if (channel.isRoot())
            for (int r = 0; r < size; ++r)
                for (const std::int64_t row : pointRows(n, size, r))
                    for (int c = 0; c < 3; ++c)
                        packed.push_back(solve.values[static_cast<std::size_t>(3 * row + c)]);
        own = channel.scatterFromRoot(packed, 3 * static_cast<std::int64_t>(points.size()));
    }
    std::vector<double> forces(3 * faces.size());
    for (std::size_t k = 0; k < forces.size(); ++k)
        forces[k] = -own[k];
    Message reply;
    reply.kind = MessageKind::Forces;
    if (mode == "rows")
    {
        channel.send(reply);
        channel.sendOwnRows(forces);
        return;
    }
    const std::vector<double> gathered = channel.gatherToRoot(forces); // rank order = row order
    reply.values = gathered;
    channel.send(reply);
}

// One exchange on the solid side (the forces end on its root).
void solidExchange(Channel& channel, const std::string& mode, const std::vector<double>& whole,
                   const RowMap& pointMap, const RowMap& faceMap)
{
    std::vector<double> forces;
    Message solve;
    solve.kind = MessageKind::Solve;
    if (mode == "rows")
    {
        channel.send(solve);
        channel.scatterRows(pointMap, whole);
        channel.receive(MessageKind::Forces);
        forces = channel.gatherRows(faceMap);
    }
    else
    {
        solve.values = whole;
        channel.send(solve);
        forces = channel.receive(MessageKind::Forces).values;
    }
    if (channel.isRoot() && forces.size() != whole.size())
        throw std::runtime_error("exchange-bench: " + std::to_string(forces.size()) +
                                 " forces came back for " + std::to_string(whole.size()) +
                                 " displacements");
}

void run(const LaunchOptions& launch, const Flags& flags, std::optional<Channel>& slot)
{
    const bool fluid = flags.side == "fluid";
    Identity self;
    self.role = fluid ? Role::Fluid : Role::Solid;
    self.program = "exchange-bench";
    self.interfaceSizes = {static_cast<std::int64_t>(flags.points.size())};
    slot.emplace(Channel::open(launch, self));
    Channel& channel = *slot;
    const int fluidRanks = fluid ? channel.localSize() : channel.peer().ranks;

    // one point and one face array per size
    std::vector<RowMap> maps;
    if (fluid)
    {
        std::vector<std::vector<std::int64_t>> rows;
        for (const std::int64_t n : flags.points)
        {
            rows.push_back(pointRows(n, channel.localSize(), channel.localRank()));
            rows.push_back(faceRows(n, channel.localSize(), channel.localRank()));
        }
        channel.sendRowMaps(rows);
    }
    else
    {
        std::vector<RowShape> shapes;
        for (const std::int64_t n : flags.points)
        {
            shapes.push_back({n, 3, false});
            shapes.push_back({n, 3, true});
        }
        maps = channel.receiveRowMaps(shapes);
    }

    for (std::size_t s = 0; s < flags.points.size(); ++s)
    {
        const std::int64_t n = flags.points[s];
        const auto points = pointRows(n, fluidRanks, fluid ? channel.localRank() : 0);
        const auto faces = faceRows(n, fluidRanks, fluid ? channel.localRank() : 0);
        std::vector<double> whole;
        if (!fluid && channel.isRoot())
            for (std::int64_t i = 0; i < 3 * n; ++i)
                whole.push_back(1e-6 * static_cast<double>(i % 1000));
        std::vector<double> wall[2], cpu[2];
        const std::string modes[2] = {"root", "rows"};
        for (int k = 0; k <= flags.repeats; ++k) // k = 0: warm-up, not counted
            for (int m = 0; m < 2; ++m)          // alternating, in one invocation
            {
                const auto start = std::chrono::steady_clock::now();
                const double cpu0 = fsi::timing::processCpuSeconds();
                if (fluid)
                    fluidExchange(channel, modes[m], n, points, faces);
                else
                    solidExchange(channel, modes[m], whole, maps[2 * s], maps[2 * s + 1]);
                if (k > 0)
                {
                    wall[m].push_back(
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                            .count());
                    cpu[m].push_back(fsi::timing::processCpuSeconds() - cpu0);
                }
            }
        if (!fluid && channel.isRoot())
            for (int m = 0; m < 2; ++m)
                std::printf("exchange-bench: mode=%s points=%lld fluid_ranks=%d repeats=%d "
                            "min_ms=%.2f median_ms=%.2f us_per_point=%.3f cpu_ms=%.2f\n",
                            modes[m].c_str(), static_cast<long long>(n), fluidRanks, flags.repeats,
                            1e3 * *std::min_element(wall[m].begin(), wall[m].end()),
                            1e3 * median(wall[m]), 1e6 * median(wall[m]) / static_cast<double>(n),
                            1e3 * median(cpu[m]));
    }
    if (fluid)
        channel.receive(MessageKind::Finish);
    else
        channel.send(MessageKind::Finish, 0, 0);
    channel.close();
}
} // namespace

int main(int argc, char** argv)
{
    std::optional<Channel> channel;
    try
    {
        const LaunchOptions launch = parseLaunchOptions(argc, argv);
        initialiseMpi(argc, argv);
        const Flags flags = parse(argc, argv);
        run(launch, flags, channel);
        finaliseMpi();
        return 0;
    }
    catch (const std::exception& e)
    {
        exitOnError(e, channel ? &*channel : nullptr);
    }
}
