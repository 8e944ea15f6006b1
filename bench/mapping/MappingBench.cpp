// SPDX-License-Identifier: GPL-3.0-or-later
//
// mapping-bench [max_points] [--min N] [--kinds a,b,...] [--wendland-radius R]
//               [--wendland-solver auto|mumps|direct|iterative] [--smoothing-radius F] : set-up
//               time,
// apply time, memory and accuracy of each mapping against interface size, on a synthetic
// foil-like surface.
//
// Interface: a NACA 0012 section (chord 1 m, closed trailing edge) extruded over a span of 1 m,
// open ends. Solid side (source): n nodes, n_c around the section (clustered towards the
// leading edge, x = 1 - cos(pi u / 2)) times n_c / 2 + 1 along the span, ends included.
// Fluid side (target): about 2 n face centres of a different, denser grid (sqrt 2 finer each
// way, milder clustering x = 0.7 (1 - cos(pi u / 2)) + 0.3 u, shifted by 0.37 of a step): the
// centroid of each quad, so slightly inside the curved surface, as fluid face centres are.
// Sizes n = 1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6 up to max_points (default 1e5).
// Kinds: nearest-neighbour, rbf-pu (defaults), rbf-wendland-c2 (support radius 4 mean solid
// spacings, or R m with --wendland-radius; solver auto: sparse LDLT up to 2e4 source points,
// CG + incomplete Cholesky above, since the bench runs without MPI; --wendland-solver mumps: MUMPS
// LDL^T as solid-app uses it, each case then initialises MPI as a singleton in its child
// process, before the resident-set baseline; skipped above 1e5), rbf-thin-plate (dense; skipped
// above 4e3), nearest-projection (onto the solid grid's Quad4 faces, bilinear; its lin_err is
// the fluid centroids' distance to the flat faces, not round-off). Wendland lines end with
// solver=S, the solver in use. --smoothing-radius F (default 0, off): every kind with the
// target-side moving-least-squares smoothing (mapping.smoothing_radius) of radius F mean fluid
// spacings (F >= 1.5 so that every fluid point has neighbours); the lines then end with
// smoothing_m=R, the radius in m.
//
// One line per kind and size:
//   mapping-bench: kind=K n=N setup_s=X apply_s=X rss_mb=X max_rel_err=X <more fields>
// setup_s: buildMapping (checks, search trees, local/global solves), process CPU seconds;
// apply_s: one consistent apply of a 3-component field, CPU seconds per call (mean of repeats
// after a first call that sizes the workspace);
// rss_mb: peak resident set of the case minus the resident set just before set-up (point
// clouds and fields excluded; the set-up transient included), MiB; each case runs in a forked
// child so cases do not share a heap. max_rel_err: max |error| / max |f| of the smooth field
// f = (sin(3x) cos(2y) + sin(4z), cos(3z) + 2 y, sin(2x + 5y)) mapped consistently.
// More fields: n_target, setup_wall_s, apply_wall_s, conservative_s (one H^T apply, CPU),
// peak_rss_mb (absolute), lin_err (the same error for a linear field: round-off for RBF kinds).
// CPU seconds are the figures to compare on a shared machine; wall seconds show the load.
#include "fsi/timing/Clock.hpp"
#include "mapping/Mapping.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <mpi.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace fsi::mapping;

namespace
{
const double pi = std::acos(-1.0);

double thickness(double x)
{
    x = std::clamp(x, 0.0, 1.0);
    return 0.6 * (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x -
                  0.1036 * x * x * x * x);
}

// Point of the section at loop parameter v in [0, 1): upper side LE -> TE, lower side TE -> LE.
Eigen::RowVector2d section(double v, bool fluid)
{
    v -= std::floor(v);
    const double u = v < 0.5 ? 2.0 * v : 2.0 * (1.0 - v);
    const double cosine = 1.0 - std::cos(0.5 * pi * u);
    const double x = fluid ? 0.7 * cosine + 0.3 * u : cosine;
    return {x, (v < 0.5 ? 1.0 : -1.0) * thickness(x)};
}

// Solid: nAround x (nAround / 2 + 1) nodes, span ends included.
PointCloud solidFoil(int nAround)
{
    const int nSpan = nAround / 2 + 1;
    PointCloud p(Eigen::Index(nAround) * nSpan, 3);
    for (int j = 0; j < nSpan; ++j)
        for (int i = 0; i < nAround; ++i)
        {
            const Eigen::RowVector2d xy = section(double(i) / nAround, false);
            p.row(Eigen::Index(j) * nAround + i) << xy(0), xy(1), double(j) / (nSpan - 1);
        }
    return p;
}

// The solid grid's Quad4 faces (closed around the section): nearest-projection's source surface.
SourceSurface solidFaces(int nAround)
{
    const int nSpan = nAround / 2 + 1;
    SourceSurface surface;
    for (int j = 0; j + 1 < nSpan; ++j)
        for (int i = 0; i < nAround; ++i)
        {
            const int next = (i + 1) % nAround;
            const int quad[4] = {j * nAround + i, j * nAround + next, (j + 1) * nAround + next,
                                 (j + 1) * nAround + i};
            surface.faces.add(fsi::mesh::CellType::Quad4, quad, 4);
        }
    return surface;
}

// Fluid: centroids of the mAround x mSpan quads of a grid shifted by 0.37 of a step.
PointCloud fluidFoil(int mAround, int mSpan)
{
    PointCloud p(Eigen::Index(mAround) * mSpan, 3);
    for (int j = 0; j < mSpan; ++j)
        for (int i = 0; i < mAround; ++i)
        {
            const Eigen::RowVector2d a = section((i + 0.37) / mAround, true);
            const Eigen::RowVector2d b = section((i + 1.37) / mAround, true);
            const Eigen::RowVector2d xy = 0.5 * (a + b); // the two span edges share the corners
            p.row(Eigen::Index(j) * mAround + i) << xy(0), xy(1), (j + 0.5) / mSpan;
        }
    return p;
}

Values field(const PointCloud& x, bool linear)
{
    Values f(x.rows(), 3);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        const double a = x(i, 0), b = x(i, 1), c = x(i, 2);
        if (linear)
            f.row(i) << 1 + 2 * a - b, 3 * c - a, 0.5 + b + c;
        else
            f.row(i) << std::sin(3 * a) * std::cos(2 * b) + std::sin(4 * c),
                std::cos(3 * c) + 2 * b, std::sin(2 * a + 5 * b);
    }
    return f;
}

double relativeError(const Values& got, const Values& want)
{
    return (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
}

// VmRSS or VmHWM of this process [MiB].
double statusMiB(const char* key)
{
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0)
            return std::atof(line.c_str() + std::strlen(key) + 1) / 1024.0; // kB
    return std::nan("");
}

// Resets VmHWM to the current resident set (Linux >= 4.0); false when not possible.
bool resetPeak()
{
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return static_cast<bool>(out);
}

struct Timing
{
    double cpu = 0, wall = 0; // per call [s]
};

// Mean time of repeated calls (at least 0.3 s CPU, at most 200 calls) after one untimed call,
// which sizes the mapping's workspace.
template <class F> Timing timePerCall(F&& call)
{
    call();
    int calls = 0;
    const double cpu0 = fsi::timing::processCpuSeconds(), wall0 = fsi::timing::wallSeconds();
    do
    {
        call();
        ++calls;
    } while (fsi::timing::processCpuSeconds() - cpu0 < 0.3 && calls < 200);
    return {(fsi::timing::processCpuSeconds() - cpu0) / calls,
            (fsi::timing::wallSeconds() - wall0) / calls};
}

// One case, in the calling (child) process; prints its line. wendlandRadius [m], 0: 4 spacings.
// smoothing: the target-side smoothing radius in mean fluid spacings (0: off).
void runCase(const std::string& kind, long size, double wendlandRadius,
             const std::string& wendlandSolver, double smoothing)
{
    const int nAround = 2 * std::max(2, int(std::lround(std::sqrt(2.0 * size) / 2.0)));
    const PointCloud s = solidFoil(nAround);
    const int mAround = int(std::lround(std::sqrt(2.0) * nAround));
    const PointCloud t = fluidFoil(mAround, std::max(1, mAround / 2));
    const double h = 2.03 / nAround;  // mean solid spacing (perimeter ~2.03 m) [m]
    const double ht = 2.03 / mAround; // mean fluid spacing [m]
    const Values smooth = field(s, false), linear = field(s, true);
    const Values smoothExact = field(t, false), linearExact = field(t, true);
    Values mapped(t.rows(), 3), back(s.rows(), 3);

    MappingParameters params;
    params.strategy = mappingType(kind).defaults();
    if (auto* w = params.strategy.get<WendlandParameters>())
    {
        w->supportRadius = wendlandRadius > 0.0 ? wendlandRadius : 4.0 * h;
        w->solver = wendlandSolver;
    }
    params.smoothingRadius = smoothing * ht;
    const double rss0 = statusMiB("VmRSS");
    const bool peakReset = resetPeak();
    const double cpu0 = fsi::timing::processCpuSeconds(), wall0 = fsi::timing::wallSeconds();
    const SourceSurface faces = solidFaces(nAround);
    const auto mapping = buildMapping(params, s, t, &faces);
    const double setupCpu = fsi::timing::processCpuSeconds() - cpu0,
                 setupWall = fsi::timing::wallSeconds() - wall0;
    const Timing consistent = timePerCall([&] { mapping->applyConsistent(smooth, mapped); });
    const double error = relativeError(mapped, smoothExact);
    mapping->applyConsistent(linear, mapped);
    const double linearError = relativeError(mapped, linearExact);
    const Timing conservative = timePerCall([&] { mapping->applyConservative(smoothExact, back); });
    const double peak = statusMiB("VmHWM");
    const auto* wendland = dynamic_cast<const RbfWendlandC2*>(mapping.get());
    std::string solver = wendland ? " solver=" + wendland->solverInUse() : "";
    if (params.smoothingRadius > 0.0)
        solver += " smoothing_m=" + std::to_string(params.smoothingRadius);
    std::printf("mapping-bench: kind=%s n=%ld setup_s=%.3g apply_s=%.3g rss_mb=%.0f "
                "max_rel_err=%.2e n_target=%ld setup_wall_s=%.3g apply_wall_s=%.3g "
                "conservative_s=%.3g peak_rss_mb=%.0f lin_err=%.1e%s%s\n",
                kind.c_str(), long(s.rows()), setupCpu, consistent.cpu, peak - rss0, error,
                long(t.rows()), setupWall, consistent.wall, conservative.cpu, peak, linearError,
                solver.c_str(), peakReset ? "" : " (peak not reset: rss_mb includes the clouds)");
    std::fflush(stdout);
}

long sizeLimit(const std::string& kind)
{
    if (kind == "rbf-thin-plate")
        return 4000;
    if (kind == "rbf-wendland-c2")
        return 100000;
    return 0;
}
} // namespace

int main(int argc, char** argv)
try
{
    long maxPoints = 100000, minPoints = 1000;
    double wendlandRadius = 0.0, smoothing = 0.0;
    std::string wendlandSolver = "auto";
    std::vector<std::string> kinds{"nearest-neighbour", "rbf-pu", "rbf-wendland-c2",
                                   "rbf-thin-plate", "nearest-projection"};
    for (int a = 1; a < argc; ++a)
    {
        const std::string arg = argv[a];
        if (arg == "--min" && a + 1 < argc)
            minPoints = std::atol(argv[++a]);
        else if (arg == "--kinds" && a + 1 < argc)
        {
            kinds.clear();
            std::stringstream list(argv[++a]);
            for (std::string kind; std::getline(list, kind, ',');)
                kinds.push_back(kind);
        }
        else if (arg == "--wendland-radius" && a + 1 < argc)
            wendlandRadius = std::atof(argv[++a]);
        else if (arg == "--wendland-solver" && a + 1 < argc)
        {
            wendlandSolver = argv[++a];
            if (wendlandSolver != "auto" && wendlandSolver != "mumps" &&
                wendlandSolver != "direct" && wendlandSolver != "iterative")
                throw std::runtime_error("--wendland-solver must be auto, mumps, direct or "
                                         "iterative (got '" +
                                         wendlandSolver + "')");
        }
        else if (arg == "--smoothing-radius" && a + 1 < argc)
        {
            smoothing = std::atof(argv[++a]);
            if (!(smoothing == 0.0 || (smoothing >= 1.5 && smoothing <= 100.0)))
                throw std::runtime_error("--smoothing-radius must be 0 (off) or in [1.5, 100] "
                                         "mean fluid spacings (got '" +
                                         std::string(argv[a]) + "')");
        }
        else if (!arg.empty() && arg[0] != '-')
            maxPoints = std::atol(arg.c_str());
        else
            throw std::runtime_error("usage: mapping-bench [max_points] [--min N] "
                                     "[--kinds nearest-neighbour,rbf-pu,...] "
                                     "[--wendland-radius R] [--wendland-solver S] "
                                     "[--smoothing-radius F]");
    }
    for (const std::string& kind : kinds)
        for (long size : {1000L, 3000L, 10000L, 30000L, 100000L, 300000L, 1000000L})
        {
            if (size < minPoints || size > maxPoints)
                continue;
            if (sizeLimit(kind) > 0 && size > sizeLimit(kind))
            {
                std::printf("mapping-bench: kind=%s n=%ld skipped (above %ld points: too slow or "
                            "too large)\n",
                            kind.c_str(), size, sizeLimit(kind));
                std::fflush(stdout);
                continue;
            }
            const pid_t child = fork();
            if (child < 0)
                throw std::runtime_error("fork failed");
            if (child == 0)
            {
                int status = 0;
                // MUMPS needs MPI: a singleton in this child only (fork after MPI_Init is not
                // allowed, so the parent never initialises it).
                const bool withMpi = kind == "rbf-wendland-c2" && wendlandSolver == "mumps";
                if (withMpi)
                    MPI_Init(nullptr, nullptr);
                try
                {
                    runCase(kind, size, wendlandRadius, wendlandSolver, smoothing);
                }
                catch (const std::exception& e)
                {
                    std::printf("mapping-bench: kind=%s n=%ld failed: %s\n", kind.c_str(), size,
                                e.what());
                    status = 1;
                }
                std::fflush(stdout);
                if (withMpi)
                    MPI_Finalize();
                std::_Exit(status);
            }
            int status = 0;
            waitpid(child, &status, 0);
            if (!WIFEXITED(status))
                std::printf("mapping-bench: kind=%s n=%ld failed: child ended by signal %d\n",
                            kind.c_str(), size, WIFSIGNALED(status) ? WTERMSIG(status) : 0);
            std::fflush(stdout);
        }
    return 0;
}
catch (const std::exception& e)
{
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
