// SPDX-License-Identifier: GPL-3.0-or-later
#include "Standalone.hpp"

#include "config/SolidConfig.hpp"
#include "config/YamlReader.hpp"
#include "fe/StructuralSolver.hpp"
#include "io/AtomicFile.hpp"
#include "io/CsvHistory.hpp"
#include "io/VtuWriter.hpp"
#include "material/Material.hpp"
#include "mesh/Mesh.hpp"
#include "schedule/Schedule.hpp"
#include "setup/SolidSetup.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fsi::app
{
namespace fs = std::filesystem;

std::string usageText()
{
    return "usage: solid-app CONFIG.yaml [--out DIR] [--restart] [--launch mpmd|port]\n"
           "                 [--port-file PATH] [--comm-timeout SECONDS]\n"
           "       solid-app --help\n"
           "Runs the structural problem of CONFIG.yaml (the keys: config/solid.example.yaml);\n"
           "a config with a top-level 'coupling:' block runs coupled with fluid-app\n"
           "(config/coupled.example.yaml). Parallel: mpirun -np N solid-app CONFIG.yaml.\n"
           "Options:\n"
           "  --out DIR               output folder (default: solid.output.folder of the config)\n"
           "  --restart               coupled runs: continue from DIR/checkpoint/latest\n"
           "  --launch mpmd|port      coupled runs: how to meet fluid-app (overrides\n"
           "                          coupling.launch.mode): one mpirun A : B (mpmd) or an MPI\n"
           "                          port published in a file (port)\n"
           "  --port-file PATH        port mode: the file solid-app writes its port name to\n"
           "                          (overrides coupling.launch.port_file)\n"
           "  --comm-timeout SECONDS  bound of every wait on fluid-app (overrides\n"
           "                          coupling.launch.timeout; default 600)\n"
           "  -h, --help              this text\n"
           "Exit status: 0 done, 1 bad input or a failed run (one line 'error: ...' on stderr),\n"
           "2 a standalone level did not converge.\n";
}

RunOptions parseArguments(int argc, char** argv)
{
    RunOptions o;
    const std::string usage = "usage: solid-app CONFIG.yaml [--out DIR] [--restart] (solid-app "
                              "--help lists every option)";
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "--out")
        {
            if (i + 1 >= argc)
                throw std::runtime_error("--out needs a folder; " + usage);
            o.outputFolder = argv[++i];
        }
        else if (a == "--restart")
            o.restart = true;
        else if (a == "-h" || a == "--help")
            o.help = true;
        else if (!a.empty() && a[0] == '-')
            throw std::runtime_error("unknown option '" + a + "'; " + usage);
        else if (o.configFile.empty())
            o.configFile = a;
        else
            throw std::runtime_error("more than one config file given; " + usage);
    }
    if (o.configFile.empty() && !o.help)
        throw std::runtime_error("no config file given; " + usage);
    return o;
}

int runStandalone(const config::Block& root, const RunOptions& options)
{
    const auto wallStart = std::chrono::steady_clock::now();
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const config::SolidConfig cfg = config::SolidConfig::fromRoot(root, options.configFile);
    const std::string out = options.outputFolder.empty() ? cfg.output.folder : options.outputFolder;
    if (rank == 0)
        std::printf("%s", cfg.echo().c_str());
    const mesh::Mesh mesh =
        mesh::readGmsh(cfg.mesh.file, {cfg.mesh.volume, setup::surfaceGroups(cfg)}, rank != 0);
    setup::checkWatchPoints(cfg, mesh);
    const auto law = material::makeMaterial(cfg.material, cfg.kinematics);
    fe::ProblemDefinition problem = setup::problemFromConfig(cfg);
    problem.printIterations = true;
    fe::StructuralSolver solver(MPI_COMM_WORLD, mesh, *law, problem);
    if (rank == 0)
    {
        // Only now that the input is known to be good: a failed start leaves the folder as it was.
        setup::prepareOutputFolder(out, false);
        io::writeFileAtomically((fs::path(out) / "config.echo.yaml").string(), cfg.echo());
        std::printf("solid-app: %d nodes, %d cells (", mesh.numNodes(), mesh.cells.size());
        for (const auto& [name, count] : mesh.cellTypeCounts())
            std::printf(" %s:%d", name.c_str(), count);
        std::printf(" ), %d free dofs, %d rank(s), material %s\n", solver.numFreeDofs(), ranks,
                    law->name().c_str());
        std::printf("solid-app: linear solver MUMPS, %s; BLAS: %s\n",
                    linalg::describe(solver.linearSolver().options()).c_str(),
                    linalg::blasDescription().c_str());
    }
    std::vector<std::string> names, extraColumns;
    std::vector<std::array<double, 3>> points;
    for (const auto& w : cfg.output.watch)
    {
        names.push_back(w.name);
        points.push_back(w.point);
    }
    // history.csv: watch-point displacement, then Cauchy stress and strain at each watch point,
    // then the reaction force on each support (clamped groups, prescribed-displacement surfaces).
    const char* components[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    for (const auto& name : names)
        for (const char* quantity : {"_sigma_", "_eps_"})
            for (const char* c : components)
                extraColumns.push_back(name + quantity + c);
    // reactions: every clamped group and every surface with prescribed displacements
    std::vector<std::string> supports = cfg.mesh.clamped;
    for (const auto& d : cfg.loads.displacements)
        if (std::find(supports.begin(), supports.end(), d.surface) == supports.end())
            supports.push_back(d.surface);
    for (const auto& group : supports)
        for (const char* c : {"x", "y", "z"})
            extraColumns.push_back("reaction_" + group + "_" + c);
    io::CsvHistory history((fs::path(out) / "history.csv").string(), mesh, names, points,
                           extraColumns);
    std::vector<int> watchNodes;
    for (std::size_t k = 0; k < names.size(); ++k)
        watchNodes.push_back(history.node(k));
    io::PvdSeries series((fs::path(out) / "solid.pvd").string());
    std::string levels =
        "level,time,dt,load_factor,newton_iterations,load_cuts,residual,factorizations,wall_s\n";

    // Level times: planned (steady, uniform, list, geometric) or following the solution
    // (adaptive: the relative change of the displacement field over each level).
    const std::unique_ptr<schedule::Schedule> schedule = cfg.time.schedule.make();
    std::vector<double> previousU(solver.numDofs(), 0.0);
    std::size_t levelCount = 0;
    for (std::size_t n = 0;; ++n)
    {
        // uniform reports its dt bitwise-constant: the factorization can be reused
        const material::TimeStep levelStep{schedule->time(), schedule->lastStep()};
        const double factor = cfg.time.factorAt(levelStep.time);
        if (rank == 0)
            std::printf("level %zu  t = %g s  dt = %g s  load factor %g\n", n, levelStep.time,
                        levelStep.dt, factor);
        const auto report = solver.solve(levelStep, {}, factor);
        if (rank == 0)
            std::printf(
                "  %s in %d Newton iterations (|R| %.3e -> %.3e N), %d factorizations so far; "
                "assembly %.3f s, linear solver %.3f s\n",
                report.converged ? "converged" : "NOT converged", report.newtonIterations,
                report.initialResidual, report.finalResidual, solver.factorizationCount(),
                report.assemblySeconds, report.linearSolveSeconds);
        if (!report.converged)
        {
            if (rank == 0)
                std::fprintf(stderr, "error: %s: level %zu (t = %g s) did not converge: %s\n",
                             options.configFile.c_str(), n, levelStep.time, report.message.c_str());
            return 2;
        }
        solver.acceptLevel();
        const bool last = !schedule->hasNext();
        // the results of the accepted level (stress with the level's own history increment)
        std::vector<double> extra;
        for (const auto& at : solver.stressAndStrainAt(watchNodes))
        {
            extra.insert(extra.end(), at.stress.data(), at.stress.data() + 6);
            extra.insert(extra.end(), at.strain.data(), at.strain.data() + 6);
        }
        for (const auto& group : supports)
        {
            const Eigen::Vector3d r = solver.reactionForce(group);
            extra.insert(extra.end(), r.data(), r.data() + 3);
        }
        std::vector<material::Vector6> nodal, cellStress;
        const bool writeVtu = cfg.output.vtu && (n % cfg.output.every == 0 || last);
        if (writeVtu)
            solver.cauchyStress(nodal, cellStress);
        if (rank == 0)
        {
            history.record(levelStep.time, solver.displacement(), extra);
            if (writeVtu)
            {
                char name[64];
                std::snprintf(name, sizeof name, "solid_%05zu.vtu", n);
                io::writeVtu((fs::path(out) / name).string(), mesh,
                             {&solver.displacement(), &nodal, &cellStress}, cfg.output.binary);
                series.add(levelStep.time, name);
                series.write();
            }
            const double wall =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
            char row[256];
            std::snprintf(row, sizeof row, "%zu,%.10g,%.10g,%.10g,%d,%d,%.6e,%d,%.3f\n", n,
                          levelStep.time, levelStep.dt, factor, report.newtonIterations,
                          report.loadCuts, report.finalResidual, solver.factorizationCount(), wall);
            levels += row;
            io::writeFileAtomically((fs::path(out) / "levels.csv").string(), levels);
        }
        if (last)
        {
            levelCount = n + 1;
            break;
        }
        // relative change of the displacement field over the level just accepted
        const auto& u = solver.displacement();
        double du = 0.0, umax = 0.0;
        for (int node = 0; node < mesh.numNodes(); ++node)
        {
            double d2 = 0.0, u2 = 0.0;
            for (int i = 0; i < 3; ++i)
            {
                d2 += (u[3 * node + i] - previousU[3 * node + i]) *
                      (u[3 * node + i] - previousU[3 * node + i]);
                u2 += u[3 * node + i] * u[3 * node + i];
            }
            du = std::max(du, d2);
            umax = std::max(umax, u2);
        }
        previousU = u;
        schedule->advance(umax > 0.0 ? std::sqrt(du / umax) : 0.0);
    }
    if (rank == 0)
    {
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
        for (std::size_t k = 0; k < names.size(); ++k)
        {
            const int node = history.node(k);
            const auto& u = solver.displacement();
            std::printf("watch %s: node %d at distance %.3e m, u = (%.6e, %.6e, %.6e) m\n",
                        names[k].c_str(), node, history.distance(k), u[3 * node], u[3 * node + 1],
                        u[3 * node + 2]);
        }
        const auto& st = solver.linearSolver().statistics();
        std::printf(
            "solid-app: linear solver totals: analysis %.2f s (cpu %.2f, ordering %.2f), "
            "factorization %.2f s (cpu %.2f), solve %.2f s (cpu %.2f); factorization "
            "memory %lld MB (estimate %lld MB), BLR %s (flops %.3g of %.3g full rank, "
            "%d refinement steps, %d fallbacks), last checked residual %.2e (backward error "
            "%.1e)\n",
            st.analysisSeconds, st.analysisCpuSeconds, st.orderingSeconds, st.factorizationSeconds,
            st.factorizationCpuSeconds, st.solveSeconds, st.solveCpuSeconds,
            st.factorizationMemoryMb, st.estimatedMemoryMb, st.lowRankActive ? "on" : "off",
            st.lowRankFlops, st.fullRankFlops, st.refinementSteps, st.lowRankFallbacks,
            st.lastRelativeResidual, st.lastBackwardError);
        if (!st.lastResiduals.empty())
        {
            std::printf("solid-app: BLR residuals of the last checked solve:");
            for (double r : st.lastResiduals)
                std::printf(" %.2e", r);
            std::printf("\n");
        }
        std::printf("solid-app: done, %zu level(s), %d analyses, %d factorizations, wall %.3f s, "
                    "output in %s\n",
                    levelCount, solver.analysisCount(), solver.factorizationCount(), wall,
                    out.c_str());
    }
    return 0;
}

} // namespace fsi::app
