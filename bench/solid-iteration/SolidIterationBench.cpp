// SPDX-License-Identifier: GPL-3.0-or-later
// solid-iteration-bench: the solid's share of a coupled history without the fluid. Builds the
// structural problem of a solid config (e.g. the coarse hydrofoil's viscoelastic.yaml as run by
// scripts/bench-fsi), then replays a schedule of time levels and coupling iterations the way
// driver::CoupledDriver calls the solver: per coupling iteration solve() with new interface loads
// (what the driver counts as solid time), per level acceptLevel(), the watch-point and reaction
// probes, the VTU output and the checkpoint state.
//
// Prints one line per call (rank 0) and a breakdown: wall and CPU seconds of solve() split into
// element assembly, linear solves (back-substitutions / CG on a stale factor / factorizations),
// with iteration counts; acceptLevel, probes, output, checkpoint; and the mean solid seconds per
// coupling iteration. Ends with the final displacement at the watch points (to compare runs).
//
// usage: solid-iteration-bench --config FILE [--mesh FILE] [--schedule coupling.csv]
//                              [--interface DIR] [--out DIR] [--no-output] [--quiet]
//   --config     solid config (its solid block is used; a coupled config is fine)
//   --mesh       replaces solid.mesh.file
//   --schedule   a coupled run's coupling.csv: its levels (time) and coupling iterations per
//                level; default: the coarse hydrofoil IQN-ILS history of verification/hydrofoil
//                (27 levels, 87 coupling iterations)
//   --interface  a coupled run's interface/ folder (level_NNNN.csv: accepted nodal forces at
//                the wetted nodes, in the solver's wetted-node order): iteration k of level L of
//                n_L iterations is loaded with F_L + (F_{L-1} - F_L) 0.2^(k-1) (k < n_L) and
//                F_L at k = n_L; default: a synthetic lift/drag load drifting over the levels
//   --out        folder for the VTU files (default /tmp/solid-iteration-bench); --no-output
//                skips them
// Not a test: performance is measured here, never asserted.
#include "config/SolidConfig.hpp"
#include "config/YamlReader.hpp"
#include "fe/StructuralSolver.hpp"
#include "fsi/timing/Clock.hpp"
#include "io/VtuWriter.hpp"
#include "material/Material.hpp"
#include "mesh/Mesh.hpp"
#include "setup/SolidSetup.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fsi;

namespace
{
namespace fs = std::filesystem;

struct Args
{
    std::string config, mesh, schedule, interface, out = "/tmp/solid-iteration-bench";
    bool output = true, quiet = false;
    double refactorDrift = -1.0; // < 0: the config's (default 0: never)
    bool recycle = true;         // fe::ProblemDefinition::recycleSolutions
};

[[noreturn]] void usage(const std::string& what)
{
    throw std::invalid_argument("solid-iteration-bench: " + what +
                                "; usage: solid-iteration-bench --config FILE [--mesh FILE] "
                                "[--schedule coupling.csv] [--interface DIR] [--out DIR] "
                                "[--no-output] [--refactor-drift X] [--no-recycle] [--quiet]");
}

Args parse(int argc, char** argv)
{
    Args a;
    for (int i = 1; i < argc; ++i)
    {
        const std::string key = argv[i];
        auto next = [&]() -> std::string
        {
            if (i + 1 >= argc)
                usage(key + " needs a value");
            return argv[++i];
        };
        if (key == "--config")
            a.config = next();
        else if (key == "--mesh")
            a.mesh = next();
        else if (key == "--schedule")
            a.schedule = next();
        else if (key == "--interface")
            a.interface = next();
        else if (key == "--out")
            a.out = next();
        else if (key == "--refactor-drift")
            a.refactorDrift = std::stod(next());
        else if (key == "--no-output")
            a.output = false;
        else if (key == "--no-recycle")
            a.recycle = false;
        else if (key == "--quiet")
            a.quiet = true;
        else
            usage("unknown argument " + key);
    }
    if (a.config.empty())
        usage("--config is required");
    return a;
}

struct Level
{
    double time = 0.0;
    int iterations = 1;
};

// The coarse hydrofoil's IQN-ILS history (verification/hydrofoil/bench-fsi.txt, 2026-12-01).
std::vector<Level> defaultSchedule()
{
    const double times[] = {0,       0.5,     2,       6.5,     20,      35,      50,
                            92.9302, 157.802, 223.875, 291.937, 360,     563.788, 737.064,
                            935.844, 1130.41, 1358.28, 1571.84, 1773.02, 2005.43, 2236.98,
                            2444.61, 2685.75, 2922.39, 3166.33, 3394.76, 3600};
    const int iterations[] = {6, 3, 2, 7, 4, 3, 2, 4, 3, 3, 2, 5, 4, 3,
                              2, 3, 2, 2, 3, 2, 2, 4, 4, 2, 1, 5, 4};
    std::vector<Level> levels;
    for (std::size_t k = 0; k < std::size(times); ++k)
        levels.push_back({times[k], iterations[k]});
    return levels;
}

// coupling.csv: level,time,iteration,... -> per level its time and last iteration.
std::vector<Level> readSchedule(const std::string& file)
{
    std::ifstream in(file);
    if (!in)
        throw std::runtime_error(file + ": cannot be read (--schedule)");
    std::map<int, Level> byLevel;
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line))
    {
        std::istringstream s(line);
        std::string level, time, iteration;
        if (!std::getline(s, level, ',') || !std::getline(s, time, ',') ||
            !std::getline(s, iteration, ','))
            continue;
        Level& l = byLevel[std::stoi(level)];
        l.time = std::stod(time);
        l.iterations = std::max(l.iterations, std::stoi(iteration));
    }
    std::vector<Level> levels;
    for (const auto& [k, l] : byLevel)
        levels.push_back(l);
    if (levels.empty())
        throw std::runtime_error(file + ": no levels (--schedule expects a coupling.csv)");
    return levels;
}

// level_NNNN.csv of a coupled run: x,y,z,ux,uy,uz,fx,fy,fz per wetted node (after a comment).
std::vector<double> readInterfaceForces(const std::string& file, const std::vector<double>& xyz)
{
    std::ifstream in(file);
    if (!in)
        throw std::runtime_error(file + ": cannot be read (--interface)");
    std::vector<double> forces;
    std::string line;
    std::size_t node = 0;
    while (std::getline(in, line))
    {
        if (line.empty() || line[0] == '#' || line[0] == 'x')
            continue;
        std::istringstream s(line);
        double v[9];
        char comma = 0;
        for (int i = 0; i < 9; ++i)
            if (!(s >> v[i]) || (i < 8 && !(s >> comma)))
                throw std::runtime_error(file + ": malformed row " + std::to_string(node + 1));
        if (3 * node + 2 >= xyz.size() || std::abs(v[0] - xyz[3 * node]) +
                                                  std::abs(v[1] - xyz[3 * node + 1]) +
                                                  std::abs(v[2] - xyz[3 * node + 2]) >
                                              1e-9)
            throw std::runtime_error(file + ": row " + std::to_string(node + 1) +
                                     " is not the solver's wetted node (another mesh?)");
        forces.insert(forces.end(), {v[6], v[7], v[8]});
        ++node;
    }
    if (forces.size() != xyz.size())
        throw std::runtime_error(file + ": " + std::to_string(node) + " rows, expected " +
                                 std::to_string(xyz.size() / 3) + " wetted nodes");
    return forces;
}

// Synthetic lift and drag (about the hydrofoil's 2.4 N / 0.43 N) with a moment about the
// mid-chord, drifting by up to 30 % over the levels.
std::vector<double> syntheticForces(const std::vector<double>& xyz, int level, int levels)
{
    const std::size_t n = xyz.size() / 3;
    double xMin = 1e300, xMax = -1e300;
    for (std::size_t k = 0; k < n; ++k)
    {
        xMin = std::min(xMin, xyz[3 * k]);
        xMax = std::max(xMax, xyz[3 * k]);
    }
    const double drift = 1.0 - 0.3 * level / std::max(1, levels - 1);
    std::vector<double> f(3 * n, 0.0);
    for (std::size_t k = 0; k < n; ++k)
    {
        const double s = (xyz[3 * k] - 0.5 * (xMin + xMax)) / std::max(1e-12, xMax - xMin);
        f[3 * k] = 0.43 / n;
        f[3 * k + 1] = -2.4 * drift * (1.0 - 1.5 * s) / n;
    }
    return f;
}

// Wall and CPU seconds of one phase, summed over its calls.
struct Phase
{
    double wall = 0.0, cpu = 0.0;
    int calls = 0;
};

class Stopwatch
{
public:
    explicit Stopwatch(Phase& phase) : phase_(phase) {}
    ~Stopwatch() { stop(); }
    // Seconds of this call (wall, cpu); adds them to the phase once.
    std::pair<double, double> stop()
    {
        if (!stopped_)
        {
            wall_ = std::chrono::duration<double>(Clock::now() - wall0_).count();
            cpu_ = timing::processCpuSeconds() - cpu0_;
            phase_.wall += wall_;
            phase_.cpu += cpu_;
            ++phase_.calls;
            stopped_ = true;
        }
        return {wall_, cpu_};
    }

private:
    using Clock = std::chrono::steady_clock;
    Phase& phase_;
    Clock::time_point wall0_ = Clock::now();
    double cpu0_ = timing::processCpuSeconds();
    double wall_ = 0.0, cpu_ = 0.0;
    bool stopped_ = false;
};

int run(const Args& args)
{
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const auto root = config::Block::load(args.config);
    config::SolidConfig cfg = config::SolidConfig::fromRoot(root, args.config);
    if (!args.mesh.empty())
        cfg.mesh.file = args.mesh;
    if (cfg.mesh.wetted.empty())
        throw std::runtime_error(args.config + ": solid.mesh.wetted is required (the interface)");
    const std::vector<Level> levels =
        args.schedule.empty() ? defaultSchedule() : readSchedule(args.schedule);

    Phase setupPhase;
    Stopwatch setupWatch(setupPhase);
    const mesh::Mesh mesh =
        mesh::readGmsh(cfg.mesh.file, {cfg.mesh.volume, setup::surfaceGroups(cfg)}, true);
    const auto law = material::makeMaterial(cfg.material, cfg.kinematics);
    fe::ProblemDefinition problem = setup::problemFromConfig(cfg);
    if (args.refactorDrift >= 0.0)
        problem.refactorShearDrift = args.refactorDrift;
    problem.recycleSolutions = args.recycle;
    fe::StructuralSolver solid(MPI_COMM_WORLD, mesh, *law, problem);
    const auto [setupWall, setupCpu] = setupWatch.stop();
    const std::vector<double> xyz = solid.wettedNodeCoordinates();
    std::vector<int> watchNodes;
    for (const auto& w : cfg.output.watch)
        watchNodes.push_back(mesh.nearestNode({w.point[0], w.point[1], w.point[2]}));
    if (args.output && rank == 0)
        fs::create_directories(args.out);

    std::vector<std::vector<double>> accepted; // F_L per level
    for (std::size_t L = 0; L < levels.size(); ++L)
    {
        if (args.interface.empty())
            accepted.push_back(syntheticForces(xyz, static_cast<int>(L), levels.size()));
        else
        {
            char name[32];
            std::snprintf(name, sizeof name, "level_%04zu.csv", L);
            accepted.push_back(
                readInterfaceForces((fs::path(args.interface) / name).string(), xyz));
        }
    }
    int iterationsTotal = 0;
    for (const auto& l : levels)
        iterationsTotal += l.iterations;
    if (rank == 0)
        std::printf("solid-iteration-bench: %s, mesh %s: %d nodes, %d cells, %d free dofs, %zu "
                    "wetted nodes, %d rank(s); %zu levels, %d coupling iterations; loads %s\n"
                    "set-up (mesh, solver, pattern) wall %.3f s cpu %.3f s\n",
                    args.config.c_str(), cfg.mesh.file.c_str(), mesh.numNodes(), mesh.cells.size(),
                    solid.numFreeDofs(), xyz.size() / 3, solid.ranks(), levels.size(),
                    iterationsTotal, args.interface.empty() ? "synthetic" : args.interface.c_str(),
                    setupWall, setupCpu);

    const auto& linear = solid.linearSolver();
    Phase solveFirst, solveAgain, accept, probes, output, checkpoint;
    double assembly = 0.0, linearSeconds = 0.0;
    double factorWall = 0.0, backWall = 0.0;
    int cgIterationsTotal = 0, newtonTotal = 0;
    for (std::size_t L = 0; L < levels.size(); ++L)
    {
        const double dt = L == 0 ? 0.0 : levels[L].time - levels[L - 1].time;
        const std::vector<double>& target = accepted[L];
        std::vector<double> previous = L == 0 ? target : accepted[L - 1];
        if (L == 0)
            for (double& v : previous)
                v *= 0.9;
        for (int k = 1; k <= levels[L].iterations; ++k)
        {
            fe::InterfaceLoads loads;
            const double w = k == levels[L].iterations ? 0.0 : std::pow(0.2, k - 1);
            loads.forces.resize(target.size());
            for (std::size_t i = 0; i < target.size(); ++i)
                loads.forces[i] = target[i] + w * (previous[i] - target[i]);
            const int factorizations0 = linear.factorizationCount();
            const int cg0 = linear.reuseIterationCount();
            const int reused0 = linear.reusedSolveCount();
            const double factor0 =
                linear.statistics().factorizationSeconds + linear.statistics().analysisSeconds;
            const double back0 = linear.statistics().solveSeconds;
            Stopwatch watch(k == 1 ? solveFirst : solveAgain);
            const fe::SolveReport report = solid.solve({levels[L].time, dt}, loads);
            const auto [wall, cpu] = watch.stop();
            if (!report.converged)
                throw std::runtime_error("level " + std::to_string(L) + " iteration " +
                                         std::to_string(k) + ": " + report.message);
            const double factorS = linear.statistics().factorizationSeconds +
                                   linear.statistics().analysisSeconds - factor0;
            const double backS = linear.statistics().solveSeconds - back0;
            const int cg = linear.reuseIterationCount() - cg0;
            assembly += report.assemblySeconds;
            linearSeconds += report.linearSolveSeconds;
            factorWall += factorS;
            backWall += backS;
            cgIterationsTotal += cg;
            newtonTotal += report.newtonIterations;
            if (rank == 0 && !args.quiet)
                std::printf("level %2zu t %9.3f dt %8.3f it %d: solve wall %.4f cpu %.4f | "
                            "assembly %.4f linear %.4f (factorization %.4f, MUMPS solves %.4f) | "
                            "newton %d, CG %d (%s), factorizations +%d | %s\n",
                            L, levels[L].time, dt, k, wall, cpu, report.assemblySeconds,
                            report.linearSolveSeconds, factorS, backS, report.newtonIterations, cg,
                            linear.reusedSolveCount() > reused0 ? "stale factor" : "-",
                            linear.factorizationCount() - factorizations0, report.message.c_str());
        }
        {
            Stopwatch watch(accept);
            solid.acceptLevel();
        }
        {
            Stopwatch watch(probes);
            solid.stressAndStrainAt(watchNodes);
            for (const auto& group : cfg.mesh.clamped)
                solid.reactionForce(group);
        }
        if (args.output)
        {
            Stopwatch watch(output);
            std::vector<material::Vector6> nodal, cells;
            solid.cauchyStress(nodal, cells);
            if (rank == 0)
            {
                char name[64];
                std::snprintf(name, sizeof name, "solid_%05zu.vtu", L);
                io::writeVtu((fs::path(args.out) / name).string(), mesh,
                             {&solid.displacement(), &nodal, &cells}, cfg.output.binary);
            }
        }
        {
            Stopwatch watch(checkpoint);
            const fe::CommittedState state = solid.committedState();
            (void)state;
        }
    }
    if (rank != 0)
        return 0;
    const Phase solveAll{solveFirst.wall + solveAgain.wall, solveFirst.cpu + solveAgain.cpu,
                         solveFirst.calls + solveAgain.calls};
    auto row = [](const char* what, const Phase& p)
    {
        std::printf("  %-44s wall %8.3f s  cpu %8.3f s  calls %3d  per call wall %.4f s\n", what,
                    p.wall, p.cpu, p.calls, p.calls ? p.wall / p.calls : 0.0);
    };
    std::printf("breakdown (rank 0):\n");
    row("solve(), all coupling iterations", solveAll);
    row("  first solve of a level (new dt/history)", solveFirst);
    row("  re-solves of a level (new loads only)", solveAgain);
    std::printf("    element assembly %.3f s, linear solver %.3f s (factorizations and analysis "
                "%.3f s, MUMPS back-substitutions %.3f s; %d factorizations, %d analyses, %d "
                "solves on a stale factor with %d CG iterations), Newton iterations %d\n",
                assembly, linearSeconds, factorWall, backWall, linear.factorizationCount(),
                linear.analysisCount(), linear.reusedSolveCount(), cgIterationsTotal, newtonTotal);
    const auto& stats = linear.statistics();
    std::printf("    MUMPS: analysis %.3f s (ordering %.3f s), factorization %.3f s wall / %.3f s "
                "cpu per factorization, %lld factor entries; solve phase %.3f s wall / %.3f s "
                "cpu in all\n",
                stats.analysisSeconds, stats.orderingSeconds,
                stats.factorizationSeconds / std::max(1, linear.factorizationCount()),
                stats.factorizationCpuSeconds / std::max(1, linear.factorizationCount()),
                stats.factorEntries, stats.solveSeconds, stats.solveCpuSeconds);
    row("acceptLevel()", accept);
    row("probes (watch-point stress, reactions)", probes);
    row("output (cauchyStress + VTU)", output);
    row("checkpoint state (committedState)", checkpoint);
    std::printf("solid seconds per coupling iteration (what the driver counts, solve() only): wall "
                "%.4f s, cpu %.4f s\n",
                solveAll.wall / solveAll.calls, solveAll.cpu / solveAll.calls);
    const double perLevel = accept.wall + probes.wall + output.wall + checkpoint.wall;
    std::printf("per-level extras (accept, probes, output, checkpoint state): wall %.3f s in all, "
                "%.4f s per coupling iteration\n",
                perLevel, perLevel / solveAll.calls);
    double uMax = 0.0;
    for (double v : solid.displacement())
        uMax = std::max(uMax, std::abs(v));
    std::printf("final state: max |u_i| %.12e m", uMax);
    for (std::size_t k = 0; k < watchNodes.size(); ++k)
        std::printf("; %s u = (%.12e, %.12e, %.12e) m", cfg.output.watch[k].name.c_str(),
                    solid.displacement()[3 * watchNodes[k]],
                    solid.displacement()[3 * watchNodes[k] + 1],
                    solid.displacement()[3 * watchNodes[k] + 2]);
    std::printf("\n");
    return 0;
}
} // namespace

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int code = 0;
    try
    {
        code = run(parse(argc, argv));
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        code = 1;
    }
    MPI_Finalize();
    return code;
}
