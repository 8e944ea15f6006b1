// SPDX-License-Identifier: GPL-3.0-or-later
// The coupling protocol between solid-app (the driver) and fluid-app: the one place where the
// payload of each message kind is laid out. Both programs encode and decode through these
// functions; Message.hpp carries the generic envelope (header, values/scalars/integers/text).
// C++14 and header-only: fluid-app compiles it with OpenFOAM v1912's headers.
//
// Interface arrays are n x 3, row-major (x, y, z of entity 0, then entity 1, ...), SI units, in
// the fluid's global interface order (points: ascending undecomposed mesh point label; faces:
// undecomposed patch order). Message values travel on the local roots only; counts, scalars
// and integers reach every rank.
//
// The per-iteration arrays (displacements, forces) do not travel in the messages: they are
// distributed interface arrays (Channel::scatterRows / gatherRows, DESIGN.md section 4), which
// each fluid rank exchanges directly with the solid's root for its own points and faces.
//
//   Hello (Channel::open)  fluid: interfaceSizes = {points P, faces F}
//   InterfaceGeometry      fluid -> solid  values = point coordinates (P x 3) [m], face centres
//                                          (F x 3) [m], face area vectors (F x 3) [m^2] pointing
//                                          out of the fluid
//   row maps               fluid ranks -> solid root, once after InterfaceGeometry
//                                          (Channel::sendRowMaps / receiveRowMaps): each fluid
//                                          rank's global point numbers (array kPointRows, P rows
//                                          of 3; a point on a processor boundary is held by
//                                          every rank that has it) and face numbers (array
//                                          kFaceRows, F rows of 3, a partition), in its own order
//   Solve                  solid -> fluid  step = level, iteration; no values; scalars = {time
//                                          [s]} (the fluid's own accuracy) or {time, force
//                                          tolerance, residual drop} with integers = {min SIMPLE
//                                          iterations} (the accuracy the driver asks for);
//                                          then the point displacements [m] from the original
//                                          geometry as kPointRows rows (scatterRows)
//   Forces                 fluid -> solid  same step and iteration; no values; integers =
//                                          {SIMPLE iterations, accuracy met 0|1}; scalars =
//                                          final residuals {U, p} (and the band); then the force
//                                          of the fluid on the body per face [N] as kFaceRows
//                                          rows (gatherRows)
//   Accept                 solid -> fluid  step = level; scalars = {time [s]} (names the output)
//   Finish                 solid -> fluid  no payload
//   Abort                  either way: text = reason (Channel::sendAbort)
#pragma once

#include "fsi/comm/Errors.hpp"
#include "fsi/comm/Message.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fsi
{
namespace comm
{
namespace protocol
{

// The distributed interface arrays' indices in the row maps, and their row width.
constexpr int kPointRows = 0;
constexpr int kFaceRows = 1;
constexpr int kRowWidth = 3; // x, y, z

struct InterfaceGeometry
{
    std::vector<double> points;      // P x 3 [m]
    std::vector<double> faceCentres; // F x 3 [m]
    std::vector<double> faceAreas;   // F x 3 [m^2], out of the fluid
};

struct Solve
{
    std::int64_t level = 0;
    std::int64_t iteration = 0;
    double time = 0;                // structural time [s]
    bool accuracyGiven = false;     // false: the fluid's own controls apply
    double forceTolerance = 0;      // relative force accuracy asked
    double residualDrop = 0;        // residuals <= drop x first residuals (0: off)
    std::int64_t minIterations = 1; // SIMPLE iterations at least
};

struct Forces
{
    std::int64_t level = 0;
    std::int64_t iteration = 0;
    std::int64_t iterations = 0;   // SIMPLE iterations of the solve
    bool converged = true;         // the asked accuracy was met before the iteration cap
    std::vector<double> residuals; // final residuals {U, p}
    double band = 0; // > 0: a flow without a steady state, converged in the mean (the forces
                     // that follow are the mean); the relative half-width of the force's band
};

struct Accept
{
    std::int64_t level = 0;
    double time = 0; // [s]
};

namespace detail
{
inline void require(bool ok, const std::string& what)
{
    if (!ok)
        throw ProtocolError("fsi::comm protocol: " + what);
}

inline void append(std::vector<double>& to, const std::vector<double>& from)
{
    to.insert(to.end(), from.begin(), from.end());
}
} // namespace detail

// ---- InterfaceGeometry ----------------------------------------------------------------------

inline Message encode(const InterfaceGeometry& g)
{
    Message m;
    m.kind = MessageKind::InterfaceGeometry;
    m.values = g.points;
    detail::append(m.values, g.faceCentres);
    detail::append(m.values, g.faceAreas);
    return m;
}

// points, faces: the sizes announced in Hello. Throws ProtocolError (every rank) when the count
// does not match; the arrays are filled on the local root only.
inline InterfaceGeometry decodeGeometry(const Message& m, std::int64_t points, std::int64_t faces)
{
    detail::require(m.kind == MessageKind::InterfaceGeometry,
                    "expected InterfaceGeometry, got " + toString(m.kind));
    detail::require(m.valueCount == 3 * points + 6 * faces,
                    "the fluid sent " + std::to_string(m.valueCount) +
                        " interface geometry values, expected " +
                        std::to_string(3 * points + 6 * faces) + " (3 per point + 6 per face)");
    InterfaceGeometry g;
    if (static_cast<std::int64_t>(m.values.size()) == m.valueCount)
    {
        const auto p = m.values.begin();
        g.points.assign(p, p + 3 * points);
        g.faceCentres.assign(p + 3 * points, p + 3 * (points + faces));
        g.faceAreas.assign(p + 3 * (points + faces), p + 3 * (points + 2 * faces));
    }
    return g;
}

// ---- Solve ----------------------------------------------------------------------------------

inline Message encode(const Solve& s)
{
    Message m;
    m.kind = MessageKind::Solve;
    m.timeStep = s.level;
    m.iteration = s.iteration;
    m.scalars = {s.time};
    if (s.accuracyGiven)
    {
        m.scalars.push_back(s.forceTolerance);
        m.scalars.push_back(s.residualDrop);
        m.integers = {s.minIterations};
    }
    return m;
}

inline Solve decodeSolve(const Message& m)
{
    detail::require(m.kind == MessageKind::Solve, "expected Solve, got " + toString(m.kind));
    detail::require(m.valueCount == 0, "a Solve carries no values (the displacements follow as "
                                       "distributed rows); got " +
                                           std::to_string(m.valueCount));
    detail::require(m.scalars.size() == 1 || (m.scalars.size() == 3 && m.integers.size() == 1),
                    "a Solve carries {time} or {time, force tolerance, residual drop} with "
                    "{min iterations}; got " +
                        std::to_string(m.scalars.size()) + " scalars and " +
                        std::to_string(m.integers.size()) + " integers");
    Solve s;
    s.level = m.timeStep;
    s.iteration = m.iteration;
    s.time = m.scalars[0];
    if (m.scalars.size() == 3)
    {
        s.accuracyGiven = true;
        s.forceTolerance = m.scalars[1];
        s.residualDrop = m.scalars[2];
        s.minIterations = m.integers[0];
    }
    return s;
}

// ---- Forces ---------------------------------------------------------------------------------

inline Message encode(const Forces& f)
{
    Message m;
    m.kind = MessageKind::Forces;
    m.timeStep = f.level;
    m.iteration = f.iteration;
    m.integers = {f.iterations, f.converged ? 1 : 0};
    m.scalars = f.residuals;
    if (f.band > 0)
        m.scalars.push_back(f.band); // after {U, p}
    return m;
}

// Checks that the answer belongs to (level, iteration); the forces follow as distributed rows.
inline Forces decodeForces(Message&& m, std::int64_t level, std::int64_t iteration)
{
    detail::require(m.kind == MessageKind::Forces, "expected Forces, got " + toString(m.kind));
    detail::require(m.timeStep == level && m.iteration == iteration,
                    "the fluid answered level " + std::to_string(m.timeStep) + " iteration " +
                        std::to_string(m.iteration) + " to level " + std::to_string(level) +
                        " iteration " + std::to_string(iteration));
    detail::require(m.valueCount == 0, "a Forces message carries no values (the forces follow "
                                       "as distributed rows); got " +
                                           std::to_string(m.valueCount));
    detail::require(m.integers.size() == 2, "a Forces message carries {SIMPLE iterations, "
                                            "accuracy met}; got " +
                                                std::to_string(m.integers.size()) + " integers");
    Forces f;
    f.level = m.timeStep;
    f.iteration = m.iteration;
    f.iterations = m.integers[0];
    f.converged = m.integers[1] != 0;
    detail::require(m.scalars.size() == 2 || m.scalars.size() == 3,
                    "a Forces message carries the residuals {U, p} and, for a solve converged "
                    "in the mean, its band; got " +
                        std::to_string(m.scalars.size()) + " scalars");
    if (m.scalars.size() == 3)
    {
        f.band = m.scalars[2];
        m.scalars.pop_back();
    }
    f.residuals = std::move(m.scalars);
    return f;
}

// ---- Accept ---------------------------------------------------------------------------------

inline Message encode(const Accept& a)
{
    Message m;
    m.kind = MessageKind::Accept;
    m.timeStep = a.level;
    m.scalars = {a.time};
    return m;
}

inline Accept decodeAccept(const Message& m)
{
    detail::require(m.kind == MessageKind::Accept, "expected Accept, got " + toString(m.kind));
    detail::require(m.scalars.size() == 1, "an Accept carries {time}; got " +
                                               std::to_string(m.scalars.size()) + " scalars");
    Accept a;
    a.level = m.timeStep;
    a.time = m.scalars[0];
    return a;
}

} // namespace protocol
} // namespace comm
} // namespace fsi
