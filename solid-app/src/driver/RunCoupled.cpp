// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/RunCoupled.hpp"

#include "config/SolidConfig.hpp"
#include "config/YamlReader.hpp"
#include "driver/CommFluidPeer.hpp"
#include "driver/CoupledDriver.hpp"
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/timing/Clock.hpp"
#include "io/AtomicFile.hpp"
#include "io/VtuWriter.hpp"
#include "material/Material.hpp"
#include "mesh/Mesh.hpp"
#include "setup/SolidSetup.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

namespace fsi::driver
{

namespace
{
namespace fs = std::filesystem;

std::optional<comm::LaunchOptions> flagLaunch; // set when a launch flag was given

comm::LaunchOptions launchFrom(const LaunchParameters& p)
{
    comm::LaunchOptions o;
    o.mode = p.mode == "port" ? comm::LaunchMode::Port : comm::LaunchMode::Mpmd;
    o.portFile = p.portFile;
    o.timeoutSeconds = p.timeout;
    return o;
}

// CPU seconds (user + system, every thread) of the whole solid-app, summed over the ranks of
// comm; the sum on rank 0 (collective).
double solidRanksCpuSeconds(MPI_Comm comm)
{
    const double own = timing::processCpuSeconds();
    double sum = 0.0;
    comm::checkMpi(MPI_Reduce(&own, &sum, 1, MPI_DOUBLE, MPI_SUM, 0, comm),
                   "MPI_Reduce of the solid ranks' CPU time");
    return sum;
}
} // namespace

void takeLaunchFlags(int& argc, char** argv)
{
    bool given = false;
    for (int i = 1; i < argc; ++i)
        for (const char* flag : {"--launch", "--port-file", "--comm-timeout"})
            if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0)
                given = true;
    auto options = comm::parseLaunchOptions(argc, argv);
    if (given)
        flagLaunch = options;
}

void endMpmdLaunchOnError(const std::exception& error)
{
    if (comm::multiProgramLaunch())
        comm::exitOnError(error, nullptr, comm::ErrorScope::AllRanks);
}

int runCoupled(const config::Block& root, const std::string& configFile,
               const std::string& outputFolder, bool restart)
{
    std::optional<comm::Channel> channel;
    try
    {
        const config::SolidConfig cfg = config::SolidConfig::fromRoot(root, configFile);
        const CouplingParameters params = CouplingParameters::parse(root.block("coupling"));
        if (cfg.mesh.wetted.empty())
            throw std::runtime_error(configFile +
                                     ": solid.mesh.wetted is required in a coupled run "
                                     "(the interface surface group)");
        const comm::LaunchOptions launch = flagLaunch ? *flagLaunch : launchFrom(params.launch);

        // The mesh first (no MPI): the handshake announces the wetted node count.
        const mesh::Mesh mesh =
            mesh::readGmsh(cfg.mesh.file, {cfg.mesh.volume, setup::surfaceGroups(cfg)}, true);
        setup::checkWatchPoints(cfg, mesh);
        const long wettedNodes = static_cast<long>(mesh.surface(cfg.mesh.wetted).nodes.size());
        channel.emplace(comm::Channel::open(launch, {comm::Role::Solid, "solid-app", {wettedNodes}},
                                            {"fluid-app", 0, {}}));
        // The solver (MUMPS) and the driver use the channel's local communicator, also in their
        // destructors: they must be gone before channel->close() frees it.
        {
            const MPI_Comm comm = channel->localComm();
            const bool root = channel->isRoot();
            const std::string out = outputFolder.empty() ? cfg.output.folder : outputFolder;
            if (root)
            {
                // After the fluid connected: a failed start leaves an earlier run's folder alone.
                setup::prepareOutputFolder(out, restart);
                const std::string echo = cfg.echo() + params.echo();
                std::printf("%s", echo.c_str());
                io::writeFileAtomically((fs::path(out) / "config.echo.yaml").string(), echo);
                std::printf("solid-app: coupled with %s; %d nodes, %d cells, %ld wetted nodes, %d "
                            "rank(s)\n",
                            channel->peerName().c_str(), mesh.numNodes(), mesh.cells.size(),
                            wettedNodes, channel->localSize());
                std::printf("%s\n", cfg.material.describe().c_str());
            }
            const auto law = material::makeMaterial(cfg.material, cfg.kinematics);
            fe::StructuralSolver solid(comm, mesh, *law, setup::problemFromConfig(cfg));
            CommFluidPeer fluid(*channel);

            LevelProbes probes;
            for (const auto& w : cfg.output.watch)
                probes.push_back(std::make_unique<WatchedNodeProbe>(
                    w.name, mesh.nearestNode({w.point[0], w.point[1], w.point[2]})));
            if (params.sectionAngle)
                probes.push_back(std::make_unique<SectionAngleProbe>(*params.sectionAngle, mesh));
            // history.csv as in the standalone mode: stress and strain at the watch points, the
            // reaction force of each clamped group
            for (const auto& w : cfg.output.watch)
                probes.push_back(std::make_unique<NodeStressProbe>(
                    w.name, mesh.nearestNode({w.point[0], w.point[1], w.point[2]})));
            for (const auto& group : cfg.mesh.clamped)
                probes.push_back(std::make_unique<ReactionProbe>(group));
            CoupledDriver driver(comm, solid, &fluid, params, out, cfg.material.relaxationTimes(),
                                 std::move(probes));
            driver.setRestart(restart);

            io::PvdSeries series((fs::path(out) / "solid.pvd").string());
            bool seriesRestored = !restart;
            driver.onLevelAccepted(
                [&](const LevelRecord& r)
                {
                    if (!seriesRestored && root)
                    {
                        // Restart: the levels before this one, whose VTU files are on disk.
                        const auto& times = driver.acceptedTimes();
                        for (std::size_t k = 0; k + 1 < times.size(); ++k)
                        {
                            char name[64];
                            std::snprintf(name, sizeof name, "solid_%05zu.vtu", k);
                            if (fs::exists(fs::path(out) / name))
                                series.add(times[k], name);
                        }
                    }
                    seriesRestored = true;
                    if (!cfg.output.vtu || (r.level % cfg.output.every) != 0)
                        return;
                    std::vector<material::Vector6> nodal, cells;
                    solid.cauchyStress(nodal, cells);
                    if (!root)
                        return;
                    char name[64];
                    std::snprintf(name, sizeof name, "solid_%05d.vtu", r.level);
                    io::writeVtu((fs::path(out) / name).string(), mesh,
                                 {&solid.displacement(), &nodal, &cells}, cfg.output.binary);
                    series.add(r.time, name);
                    series.write();
                });
            const RunSummary s = driver.run();
            // cpu_s: the solid ranks' whole CPU time, waits on the fluid included
            const double cpu = solidRanksCpuSeconds(comm);
            if (root)
            {
                char row[512];
                std::snprintf(
                    row, sizeof row,
                    "levels,coupling_iterations,fluid_iterations,factorizations,wall_s,fluid_s,"
                    "solid_s,mapping_s,cpu_s\n%d,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                    s.levels, s.couplingIterations, s.fluidIterations, s.factorizations,
                    s.wallSeconds, s.fluidSeconds, s.solidSeconds, s.mappingSeconds, cpu);
                io::writeFileAtomically((fs::path(out) / "summary.csv").string(), row);
                std::printf(
                    "solid-app: done, %d levels, %d coupling iterations, %d fluid iterations, "
                    "%d factorizations; wall %.1f s (fluid %.1f, solid %.1f, mapping %.2f); "
                    "CPU of the solid ranks %.1f s; output in %s\n",
                    s.levels, s.couplingIterations, s.fluidIterations, s.factorizations,
                    s.wallSeconds, s.fluidSeconds, s.solidSeconds, s.mappingSeconds, cpu,
                    out.c_str());
            }
        }
        channel->close();
        return 0;
    }
    catch (const std::exception& e)
    {
        comm::exitOnError(e, channel ? &*channel : nullptr, comm::ErrorScope::AllRanks);
    }
}

} // namespace fsi::driver
