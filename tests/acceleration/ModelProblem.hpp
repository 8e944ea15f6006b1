// SPDX-License-Identifier: GPL-3.0-or-later
// Linear fixed-point model problems u = A u + b for the accelerator tests.
#pragma once

#include "acceleration/Accelerator.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace fsi::acceleration::test
{

// A = Q diag(lambda) Q^T with lambda evenly spread over [lambdaMin, lambdaMax] and a fixed
// orthogonal Q; with lambdaMin < -1 the plain iteration (omega = 1) diverges.
struct LinearProblem
{
    Eigen::MatrixXd a;
    Eigen::VectorXd b;

    LinearProblem(int n, double lambdaMin, double lambdaMax, unsigned seed = 7)
    {
        Eigen::MatrixXd m(n, n);
        unsigned state = seed;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
            {
                state = state * 1664525u + 1013904223u; // LCG: same numbers everywhere
                m(i, j) = double(state >> 8) / double(1u << 24) - 0.5;
            }
        const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(m).householderQ();
        Eigen::VectorXd lambda(n);
        for (int i = 0; i < n; ++i)
            lambda(i) = n == 1 ? lambdaMin : lambdaMin + (lambdaMax - lambdaMin) * i / (n - 1);
        a = q * lambda.asDiagonal() * q.transpose();
        b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
    }

    Eigen::VectorXd solve(const Eigen::VectorXd& u) const { return a * u + b; }
    Eigen::VectorXd fixedPoint() const
    {
        return (Eigen::MatrixXd::Identity(b.size(), b.size()) - a).lu().solve(b);
    }
};

struct LevelResult
{
    int solverCalls = 0; // evaluations of the solver, the last one confirming convergence
    bool converged = false;
    Eigen::VectorXd solution;
};

// One time level as the driver runs it: send u, get u_hat, test |r|/sqrt(n) < tol, update.
template <class Problem>
LevelResult runLevel(Accelerator& accelerator, const Problem& problem, Eigen::VectorXd u,
                     int maxCalls, double tolerance)
{
    LevelResult result;
    accelerator.beginLevel();
    for (result.solverCalls = 1; result.solverCalls <= maxCalls; ++result.solverCalls)
    {
        const Eigen::VectorXd output = problem.solve(u);
        const double rms = (output - u).norm() / std::sqrt(double(u.size()));
        if (!std::isfinite(rms))
            break;
        if (rms < tolerance)
        {
            result.converged = true;
            accelerator.endLevel();
            break;
        }
        u = accelerator.update(u, output);
    }
    result.solution = u;
    return result;
}

} // namespace fsi::acceleration::test
