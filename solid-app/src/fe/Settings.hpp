// SPDX-License-Identifier: GPL-3.0-or-later
// Settings of a structural problem that the config layer fills directly (no mirror structs):
// the Newton controls and a prescribed displacement. Header only, light (no MUMPS, no mesh).
#pragma once
#include <Eigen/Dense>

#include <array>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace fsi::fe
{

// Energy line search (Crisfield: secant on s(alpha) = du . R(u + alpha du)):
//   Fallback  full Newton steps first; only if that attempt fails (stall, divergence,
//             inadmissible step) the same start is retried with the line search. Where plain
//             Newton converges it takes the same iterations (slender finite-strain problems:
//             the line search would shorten good steps whose residual grows on the way).
//   Always    the line search on every step.
//   Never     plain Newton (then load cuts).
enum class LineSearch
{
    Fallback,
    Always,
    Never
};

struct NewtonSettings
{
    int maxIterations = 25;
    double residualTolerance = 1e-8;  // ||R_free|| <= rtol * max(||f_ext||, ||f_int||) + atol
    double absoluteTolerance = 1e-10; // [N]
    LineSearch lineSearch = LineSearch::Fallback;
    int maxLoadCuts = 6; // failed level: retry in 2, 4, ... 2^k load sub-steps
};

struct PrescribedDisplacement
{
    std::string surface;
    std::array<std::optional<double>, 3> value; // [m]; unset components are free
    // Optional field u(X, loadFactor) [m] of the reference position: if set it prescribes all
    // three components at each node of the surface (value is then ignored; the field gets the
    // load factor itself, e.g. a rotation angle, and is not scaled).
    std::function<Eigen::Vector3d(const Eigen::Vector3d&, double)> field;
};

// "fallback" | "always" | "never" (the config's solid.newton.line_search).
inline const char* toString(LineSearch policy)
{
    switch (policy)
    {
    case LineSearch::Always:
        return "always";
    case LineSearch::Never:
        return "never";
    case LineSearch::Fallback:
        break;
    }
    return "fallback";
}

// The policy named `name` (see toString); throws std::invalid_argument for another name.
inline LineSearch lineSearchFromName(const std::string& name)
{
    for (LineSearch p : {LineSearch::Fallback, LineSearch::Always, LineSearch::Never})
        if (name == toString(p))
            return p;
    throw std::invalid_argument("unknown line search policy '" + name + "'");
}

} // namespace fsi::fe
