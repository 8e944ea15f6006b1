// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/Quality.hpp"

#include "mapping/KdTree.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::mapping
{

namespace
{
template <class... Args> std::string format(const char* fmt, Args... args)
{
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, fmt, args...);
    return buffer;
}

std::string boxString(const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi)
{
    return format("[%.4g %.4g %.4g]..[%.4g %.4g %.4g] m", lo(0), lo(1), lo(2), hi(0), hi(1), hi(2));
}
} // namespace

std::string MappingQuality::toString() const
{
    std::string s = format("max nearest distance %.3e m (%.3g %% of interface size %.3e m), "
                           "bounding-box overlap %.3f",
                           maxNearestDistance, 100.0 * maxNearestDistance / interfaceSize,
                           interfaceSize, boundingBoxOverlap);
    if (!std::isnan(coordinateRmsError))
        s += format(", coordinate error rms %.3e m max %.3e m", coordinateRmsError,
                    coordinateMaxError);
    return s;
}

MappingQuality assessGeometry(const PointCloud& source, const PointCloud& target)
{
    if (source.rows() == 0 || target.rows() == 0)
        throw std::runtime_error("mapping: empty interface point cloud (source " +
                                 std::to_string(source.rows()) + " points, target " +
                                 std::to_string(target.rows()) + "); check the wetted surface");
    MappingQuality q;
    const Eigen::RowVector3d sLo = source.colwise().minCoeff(), sHi = source.colwise().maxCoeff();
    const Eigen::RowVector3d tLo = target.colwise().minCoeff(), tHi = target.colwise().maxCoeff();
    q.interfaceSize = (sHi - sLo).norm();
    const double flat = 1e-9 * std::max(q.interfaceSize, (tHi - tLo).norm());
    q.boundingBoxOverlap = 1.0;
    for (int a = 0; a < 3; ++a)
    {
        const double enclosing = std::max(sHi(a), tHi(a)) - std::min(sLo(a), tLo(a));
        if (enclosing <= flat)
            continue;
        const double common = std::min(sHi(a), tHi(a)) - std::max(sLo(a), tLo(a));
        q.boundingBoxOverlap *= std::max(common, 0.0) / enclosing;
    }
    KdTree tree(source);
    for (Eigen::Index t = 0; t < target.rows(); ++t)
    {
        double d = 0.0;
        tree.nearest(target.row(t).data(), &d);
        if (d > q.maxNearestDistance || q.worstTarget < 0)
        {
            q.maxNearestDistance = d;
            q.worstTarget = t;
        }
    }
    return q;
}

MappingQuality assessQuality(const Mapping& mapping, const PointCloud& source,
                             const PointCloud& target)
{
    MappingQuality q = assessGeometry(source, target);
    const Values sourceCoordinates = source;
    Values mapped(target.rows(), 3);
    mapping.applyConsistent(sourceCoordinates, mapped);
    const Eigen::VectorXd error = (mapped - Values(target)).rowwise().norm();
    q.coordinateRmsError = std::sqrt(error.squaredNorm() / static_cast<double>(error.size()));
    q.coordinateMaxError = error.maxCoeff();
    return q;
}

void checkOverlap(const PointCloud& source, const PointCloud& target, double relativeTolerance)
{
    const MappingQuality q = assessGeometry(source, target);
    const double allowed = relativeTolerance * q.interfaceSize;
    const Eigen::RowVector3d sLo = source.colwise().minCoeff(), sHi = source.colwise().maxCoeff();
    const Eigen::RowVector3d tLo = target.colwise().minCoeff(), tHi = target.colwise().maxCoeff();
    for (int a = 0; a < 3; ++a)
        if (std::max(sLo(a), tLo(a)) - std::min(sHi(a), tHi(a)) > allowed)
            throw std::runtime_error(
                "mapping: interfaces do not overlap: bounding boxes are disjoint (solid " +
                boxString(sLo, sHi) + ", fluid " + boxString(tLo, tHi) +
                "); check units and placement of both meshes");
    if (q.maxNearestDistance > allowed)
    {
        const auto p = target.row(q.worstTarget);
        throw std::runtime_error(format("mapping: interfaces do not overlap: target point "
                                        "(%.4g %.4g %.4g) m is %.3e m from the nearest source "
                                        "point, above mapping.overlap_tolerance %g x interface "
                                        "size",
                                        p(0), p(1), p(2), q.maxNearestDistance, relativeTolerance) +
                                 format(" %.3e m; check units and placement of both meshes or "
                                        "raise mapping.overlap_tolerance",
                                        q.interfaceSize));
    }
}

} // namespace fsi::mapping
