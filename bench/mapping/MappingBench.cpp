// SPDX-License-Identifier: GPL-3.0-or-later
//
// mapping-bench [max_points] : set-up and apply time of each mapping against interface size.
// Interface: a cylinder (radius 0.5 m, length 1 m); solid side N_s nodes on a structured grid,
// fluid side about 2.25 N_s points sampled differently (1.5x denser, rotated). Sizes 1e2..1e5
// for nearest-neighbour and Wendland C2 (support radius 4 solid spacings, stationary; solver
// "auto" = sparse LDLT up to 2e4 source points, CG + incomplete Cholesky above; and CG forced,
// "wendland-cg"), up to 4e3 for the thin-plate spline. Apply = 3 columns (a vector field).
// Timings are process CPU seconds (one thread), independent of the machine's load.
// Error: relative max error of f = sin(3x) cos(2y) + sin(4z) mapped consistently, and of a
// linear field (zero for the RBF kinds up to round-off).
#include "mapping/Mapping.hpp"
#include "mapping/RbfWendlandC2.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

using namespace fsi::mapping;

namespace
{
const double pi = std::acos(-1.0);

PointCloud cylinder(int nTheta, int nZ, double thetaShift, double zLo, double zHi)
{
    PointCloud p(nTheta * nZ, 3);
    for (int j = 0; j < nZ; ++j)
        for (int i = 0; i < nTheta; ++i)
        {
            const double theta = 2.0 * pi * (i + thetaShift) / nTheta;
            const double z = zLo + (zHi - zLo) * j / (nZ - 1);
            p.row(j * nTheta + i) << 0.5 * std::cos(theta), 0.5 * std::sin(theta), z;
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
            f.row(i) << std::sin(3 * a) * std::cos(2 * b) + std::sin(4 * c), std::cos(3 * c),
                std::sin(2 * a + b);
    }
    return f;
}

double relativeError(const Values& got, const Values& want)
{
    return (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
}

// Process CPU time [s]: the code is single-threaded, and CPU time does not depend on how many
// other jobs share the cores (wall time does).
double cpuSeconds()
{
    return double(std::clock()) / CLOCKS_PER_SEC;
}

template <class F> double timePerCall(F&& call)
{
    int calls = 0;
    const double start = cpuSeconds();
    do
    {
        call();
        ++calls;
    } while (cpuSeconds() - start < 0.3 && calls < 200);
    return (cpuSeconds() - start) / calls;
}
} // namespace

int main(int argc, char** argv)
try
{
    const long maxPoints = argc > 1 ? std::atol(argv[1]) : 100000;
    std::printf("%-18s %8s %8s %9s %11s %11s %11s %10s %10s  %s\n", "mapping", "N_s", "N_t",
                "h [m]", "setup [s]", "consist [s]", "conserv [s]", "err smooth", "err linear",
                "solver");
    for (const std::string label :
         {"nearest-neighbour", "rbf-wendland-c2", "wendland-cg", "rbf-thin-plate"})
    {
        const std::string type = label == "wendland-cg" ? "rbf-wendland-c2" : label;
        long limit = type == "rbf-thin-plate" ? std::min(maxPoints, 4000L) : maxPoints;
        if (label == "wendland-cg")
            limit = std::min(maxPoints, 10000L);
        for (long target : {100L, 300L, 1000L, 3000L, 10000L, 30000L, 100000L})
        {
            if (target > limit)
                break;
            // nTheta (nTheta/2 + 1) ~ target, nTheta a multiple of 4.
            int nTheta = 4 * std::max(1, int(std::lround(std::sqrt(2.0 * target) / 4.0)));
            const PointCloud s = cylinder(nTheta, nTheta / 2 + 1, 0.0, 0.0, 1.0);
            const int m = 3 * nTheta / 2, mz = 3 * nTheta / 4;
            const PointCloud t = cylinder(m, mz, 0.37, 0.5 / mz, 1.0 - 0.5 / mz);
            const double h = 2.0 * pi * 0.5 / nTheta;

            MappingParameters params;
            params.type = type;
            params.wendland.supportRadius = 4.0 * h;
            if (label == "wendland-cg")
                params.wendland.solver = "iterative";
            const double start = cpuSeconds();
            const auto mapping = buildMapping(params, s, t);
            const double setup = cpuSeconds() - start;

            const Values smooth = field(s, false), linear = field(s, true);
            Values mapped(t.rows(), 3), back(s.rows(), 3);
            const double consistent =
                timePerCall([&] { mapping->applyConsistent(smooth, mapped); });
            const double smoothError = relativeError(mapped, field(t, false));
            mapping->applyConsistent(linear, mapped);
            const double linearError = relativeError(mapped, field(t, true));
            const Values forces = field(t, false);
            const double conservative =
                timePerCall([&] { mapping->applyConservative(forces, back); });
            std::string solver = type == "rbf-thin-plate" ? "dense LU" : "-";
            if (const auto* w = dynamic_cast<const RbfWendlandC2*>(mapping.get()))
                solver = w->iterative()
                             ? "CG+IC, " + std::to_string(w->lastIterations()) + " iterations"
                             : "sparse LDLT";
            std::printf("%-18s %8ld %8ld %9.3e %11.3e %11.3e %11.3e %10.3e %10.3e  %s\n",
                        label.c_str(), long(s.rows()), long(t.rows()), h, setup, consistent,
                        conservative, smoothError, linearError, solver.c_str());
            std::fflush(stdout);
        }
    }
    return 0;
}
catch (const std::exception& e)
{
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
