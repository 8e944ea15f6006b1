// SPDX-License-Identifier: GPL-3.0-or-later
// solid-bench: one static linear-elastic solve of a structured Tet10 box (clamped at x = 0,
// gravity), through fe::StructuralSolver and linalg::SparseDirectSolver with the given linear
// solver options. Prints one line (rank 0):
//   solid-bench: dofs=N ranks=R factor_s=X solve_s=X rss_mb=X analysis_s=X ordering_s=X
//                factor_cpu_s=X cpu_s=X blr=on|off ordering=NAME residual=X mumps_mb=X
//                flops=X blr_flops=X cells=NX,NY,NZ assembly_s=X wall_s=X blas=NAME
// rss_mb is the largest peak resident set of one rank; cpu_s the process CPU time summed over
// the ranks (whole run); factor_cpu_s that of the factorization, summed over the ranks; residual
// the relative residual |f - K u| / |f| of the first solve (Newton's first iterate).
// Not a test: run by bench/solid-scaling/run.sh, one process per case (peak memory per case).
//
// usage: solid-bench [--dofs N | --cells NX NY NZ] [--aspect A:B:C] [--low-rank auto|on|off]
//                    [--tolerance EPS] [--ufsc] [--ordering metis|scotch|ptscotch|amd|amf|pord|
//                    qamd|auto] [--threads T] [--nu NU] [--verbosity V] [--no-check] [--estimate]
//   --no-check  no residual check after full-rank solves (on by default here: `residual` and
//               `residuals` then cover every variant); --estimate  analysis only: prints MUMPS'
//               memory and flop estimates (mumps_mb, flops) without factorizing.
#include "fe/StructuralSolver.hpp"
#include "fsi/timing/Clock.hpp"
#include "linalg/CsrPattern.hpp"
#include "linalg/SparseDirectSolver.hpp"
#include "material/LinearElastic.hpp"
#include "mesh/Mesh.hpp"

#include <mpi.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fsi;

namespace
{
struct Args
{
    std::array<int, 3> cells{0, 0, 0};
    std::array<int, 3> aspect{2, 1, 1};
    long dofs = 40000;
    linalg::DirectSolverOptions solver;
    std::string orderingName = "metis";
    double nu = 0.49;
    bool estimate = false; // analysis only: MUMPS' memory and flop estimates
};

[[noreturn]] void usage(const std::string& what)
{
    throw std::invalid_argument(
        "solid-bench: " + what +
        "; usage: solid-bench [--dofs N | --cells NX NY NZ] [--aspect A:B:C] "
        "[--low-rank auto|on|off] [--tolerance EPS] [--ufsc] "
        "[--ordering metis|scotch|ptscotch|amd|amf|pord|qamd|auto] [--threads T] [--nu NU] "
        "[--verbosity V] [--no-check] [--estimate]");
}

Args parse(int argc, char** argv)
{
    Args a;
    a.solver.checkResidual = true; // the residual of every variant, in the same norm
    for (int i = 1; i < argc; ++i)
    {
        const std::string key = argv[i];
        auto next = [&]() -> std::string
        {
            if (i + 1 >= argc)
                usage(key + " needs a value");
            return argv[++i];
        };
        if (key == "--dofs")
            a.dofs = std::stol(next());
        else if (key == "--cells")
            for (int c = 0; c < 3; ++c)
                a.cells[c] = std::stoi(next());
        else if (key == "--aspect")
        {
            const std::string v = next();
            if (std::sscanf(v.c_str(), "%d:%d:%d", &a.aspect[0], &a.aspect[1], &a.aspect[2]) != 3)
                usage("--aspect wants A:B:C, e.g. 2:1:1");
        }
        else if (key == "--low-rank")
        {
            const std::string v = next();
            if (v == "on")
                a.solver.lowRank = linalg::LowRank::On;
            else if (v == "off")
                a.solver.lowRank = linalg::LowRank::Off;
            else if (v == "auto")
                a.solver.lowRank = linalg::LowRank::Auto;
            else
                usage("--low-rank wants auto, on or off");
        }
        else if (key == "--tolerance")
            a.solver.lowRankTolerance = std::stod(next());
        else if (key == "--ufsc")
            a.solver.lowRankUcfs = false;
        else if (key == "--ordering")
        {
            a.orderingName = next();
            const char* names[] = {"amd",   "",     "amf",  "scotch",  "pord",
                                   "metis", "qamd", "auto", "ptscotch"};
            int found = -1;
            for (int k = 0; k < 9; ++k)
                if (a.orderingName == names[k])
                    found = k;
            if (found < 0)
                usage("unknown --ordering " + a.orderingName);
            a.solver.ordering = found;
        }
        else if (key == "--threads")
            a.solver.threadsPerRank = std::stoi(next());
        else if (key == "--nu")
            a.nu = std::stod(next());
        else if (key == "--no-check")
            a.solver.checkResidual = false;
        else if (key == "--estimate")
            a.estimate = true;
        else if (key == "--verbosity")
            a.solver.verbosity = std::stoi(next());
        else
            usage("unknown argument " + key);
    }
    a.solver.validate();
    if (a.cells[0] <= 0)
    {
        // free dofs = 3 (2 nx) (2 ny + 1) (2 nz + 1) with n = aspect * k: smallest k reaching dofs
        for (int k = 1;; ++k)
        {
            const long nx = a.aspect[0] * k, ny = a.aspect[1] * k, nz = a.aspect[2] * k;
            if (3 * (2 * nx) * (2 * ny + 1) * (2 * nz + 1) >= a.dofs || k > 1000)
            {
                a.cells = {int(nx), int(ny), int(nz)};
                break;
            }
        }
    }
    return a;
}

// Structured box of nx x ny x nz cubes of size h, each split into 6 Tet10 (Kuhn split along
// the 0-6 diagonal, conforming). Nodes on the grid of half-cells; group "clamped" at x = 0.
mesh::Mesh boxMesh(const std::array<int, 3>& n, double h)
{
    const int mx = 2 * n[0] + 1, my = 2 * n[1] + 1, mz = 2 * n[2] + 1;
    auto node = [&](int i, int j, int k) { return i + mx * (j + my * k); };
    mesh::Mesh m;
    m.source = "box";
    m.nodes.resize(3, static_cast<long>(mx) * my * mz);
    for (int k = 0; k < mz; ++k)
        for (int j = 0; j < my; ++j)
            for (int i = 0; i < mx; ++i)
                m.nodes.col(node(i, j, k)) << 0.5 * h * i, 0.5 * h * j, 0.5 * h * k;
    const int paths[6][2] = {{1, 2}, {1, 5}, {3, 2}, {3, 7}, {4, 5}, {4, 7}};
    const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    // Tet10 (Gmsh order): vertices 0..3, then edges 01, 12, 02, 03, 23, 13
    const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}};
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                for (const auto& p : paths)
                {
                    std::array<std::array<int, 3>, 4> v;
                    const int ids[4] = {0, p[0], p[1], 6};
                    for (int a = 0; a < 4; ++a)
                        v[a] = {2 * (i + corner[ids[a]][0]), 2 * (j + corner[ids[a]][1]),
                                2 * (k + corner[ids[a]][2])};
                    // positive orientation: swap vertices 1 and 2 if needed
                    auto d = [&](int a, int c) { return double(v[a][c] - v[0][c]); };
                    const double det = d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) -
                                       d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
                                       d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0));
                    if (det < 0)
                        std::swap(v[1], v[2]);
                    int cell[10];
                    for (int a = 0; a < 4; ++a)
                        cell[a] = node(v[a][0], v[a][1], v[a][2]);
                    for (int e = 0; e < 6; ++e)
                    {
                        const auto& x = v[edges[e][0]];
                        const auto& y = v[edges[e][1]];
                        cell[4 + e] = node((x[0] + y[0]) / 2, (x[1] + y[1]) / 2, (x[2] + y[2]) / 2);
                    }
                    m.cells.add(mesh::CellType::Tet10, cell, 10);
                }
    mesh::SurfaceGroup clamped;
    clamped.name = "clamped";
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
        {
            // two Tri6 per square face at x = 0 (diagonal (j, k) -> (j+1, k+1))
            const int J = 2 * j, K = 2 * k;
            const int a[6] = {node(0, J, K),     node(0, J + 2, K),     node(0, J + 2, K + 2),
                              node(0, J + 1, K), node(0, J + 2, K + 1), node(0, J + 1, K + 1)};
            const int b[6] = {node(0, J, K),         node(0, J + 2, K + 2), node(0, J, K + 2),
                              node(0, J + 1, K + 1), node(0, J + 1, K + 2), node(0, J, K + 1)};
            clamped.faces.add(mesh::CellType::Tri6, a, 6);
            clamped.faces.add(mesh::CellType::Tri6, b, 6);
        }
    for (int k = 0; k < mz; ++k)
        for (int j = 0; j < my; ++j)
            clamped.nodes.push_back(node(0, j, k));
    std::sort(clamped.nodes.begin(), clamped.nodes.end());
    m.surfaces["clamped"] = std::move(clamped);
    return m;
}

} // namespace

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    int status = 0;
    try
    {
        const auto start = std::chrono::steady_clock::now();
        const Args args = parse(argc, argv);
        const double h = 0.01; // [m]
        const mesh::Mesh mesh = boxMesh(args.cells, h);
        if (args.estimate)
        {
            // the solver's dof numbering: 3 per node off the clamped face, node by node
            std::vector<int> equation(3 * mesh.numNodes(), -1);
            int n = 0;
            for (int a = 0; a < mesh.numNodes(); ++a)
                if (mesh.nodes(0, a) > 1e-12)
                    for (int c = 0; c < 3; ++c)
                        equation[3 * a + c] = n++;
            std::vector<int> offsets{0}, dofs;
            for (int c = rank; c < mesh.cells.size(); c += ranks)
            {
                for (int k = 0; k < mesh.cells.numNodes(c); ++k)
                    for (int d = 0; d < 3; ++d)
                        dofs.push_back(equation[3 * mesh.cells.nodes(c)[k] + d]);
                offsets.push_back(static_cast<int>(dofs.size()));
            }
            linalg::DirectSolverStatistics st;
            {
                const auto pattern = linalg::CsrPattern::fromElements(n, offsets, dofs, true);
                linalg::SparseDirectSolver solver(MPI_COMM_WORLD, args.solver);
                solver.setPattern(n, pattern.tripletRows(), pattern.tripletColumns());
                solver.analyze();
                st = solver.statistics();
            }
            if (rank == 0)
                std::printf("solid-bench: estimate dofs=%d cells=%d,%d,%d mumps_mb=%lld "
                            "flops=%.3g analysis_s=%.2f\n",
                            n, args.cells[0], args.cells[1], args.cells[2], st.estimatedMemoryMb,
                            st.fullRankFlops, st.analysisSeconds);
            MPI_Finalize();
            return 0;
        }
        const double E = 47.4e6, nu = args.nu;
        const material::LinearElastic law(E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu)));
        fe::ProblemDefinition problem;
        problem.clamped = {"clamped"};
        problem.density = 1200.0;
        problem.gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
        problem.linearSolver = args.solver;
        problem.newton.maxIterations = 3;
        std::vector<double> residual;
        double factorCpu = 0.0, analysisS = 0.0, orderingS = 0.0, factorS = 0.0, solveS = 0.0,
               assemblyS = 0.0;
        linalg::DirectSolverStatistics st;
        int dofs = 0, newton = 0;
        {
            fe::StructuralSolver solid(MPI_COMM_WORLD, mesh, law, problem);
            dofs = solid.numFreeDofs();
            const fe::SolveReport report = solid.solve({0.0, 0.0});
            if (!report.converged)
                throw std::runtime_error("solid-bench: not converged: " + report.message);
            st = solid.linearSolver().statistics();
            newton = report.newtonIterations;
            assemblyS = report.assemblySeconds;
            // relative residual after the first solve: residuals[1] / reference force
            residual.push_back(report.residuals.size() > 1
                                   ? report.residuals[1] / report.referenceForce
                                   : report.finalResidual / report.referenceForce);
        }
        factorCpu = st.factorizationCpuSeconds;
        MPI_Allreduce(MPI_IN_PLACE, &factorCpu, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        analysisS = st.analysisSeconds;
        orderingS = st.orderingSeconds;
        factorS = st.factorizationSeconds;
        solveS = st.solveSeconds;
        double cpu = timing::processCpuSeconds();
        MPI_Allreduce(MPI_IN_PLACE, &cpu, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        double rssMb = usage.ru_maxrss / 1024.0;
        MPI_Allreduce(MPI_IN_PLACE, &rssMb, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (rank == 0)
        {
            std::string history;
            for (std::size_t k = 0; k < st.lastResiduals.size(); ++k)
            {
                char text[48];
                std::snprintf(text, sizeof text, "%s%.1e(%.0e)", history.empty() ? "" : "/",
                              st.lastResiduals[k], st.lastBackwardErrors[k]);
                history += text;
            }
            if (history.empty())
                history = "-";
            std::string blas = linalg::blasDescription();
            blas = blas.rfind("OpenBLAS", 0) == 0 ? "openblas" : "reference";
            std::printf("solid-bench: dofs=%d ranks=%d factor_s=%.2f solve_s=%.3f rss_mb=%.0f "
                        "analysis_s=%.2f ordering_s=%.2f factor_cpu_s=%.2f cpu_s=%.2f blr=%s "
                        "tol=%.0e ordering=%s residual=%.1e refine=%d fallback=%d mumps_mb=%lld "
                        "flops=%.3g blr_flops=%.3g newton=%d cells=%d,%d,%d assembly_s=%.2f "
                        "wall_s=%.2f blas=%s threads=%d entries=%lld blr_entries=%lld "
                        "residuals=%s\n",
                        dofs, ranks, factorS, solveS, rssMb, analysisS, orderingS, factorCpu, cpu,
                        st.lowRankActive ? "on" : "off",
                        st.lowRankActive ? args.solver.lowRankTolerance : 0.0,
                        args.orderingName.c_str(), residual[0], st.refinementSteps,
                        st.lowRankFallbacks, st.factorizationMemoryMb, st.fullRankFlops,
                        st.lowRankFlops, newton, args.cells[0], args.cells[1], args.cells[2],
                        assemblyS, wall, blas.c_str(), args.solver.threadsPerRank, st.factorEntries,
                        st.lowRankFactorEntries, history.c_str());
            std::fflush(stdout);
        }
    }
    catch (const std::exception& e)
    {
        if (rank == 0)
            std::fprintf(stderr, "%s\n", e.what());
        status = 1;
    }
    MPI_Finalize();
    return status;
}
