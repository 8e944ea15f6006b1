// SPDX-License-Identifier: GPL-3.0-or-later
//
// Set-up checks of an interface pair: how well the two clouds overlap and how well a mapping
// carries the coordinates themselves (a linear field: zero error for the RBF kinds).
#pragma once

#include "mapping/Mapping.hpp"

#include <limits>
#include <string>

namespace fsi::mapping
{

struct MappingQuality
{
    double interfaceSize = 0.0;      // m, diagonal of the source bounding box
    double maxNearestDistance = 0.0; // m, max over targets of the distance to the nearest source
    Eigen::Index worstTarget = -1;   // target index where maxNearestDistance is reached
    // Bounding-box overlap: product over axes of |intersection| / |enclosing interval|, axes
    // where both clouds are flat (extent < 1e-9 interfaceSize) skipped. 1 identical, 0 disjoint.
    double boundingBoxOverlap = 0.0;
    // Error of mapping the source coordinates consistently to the targets, |H x_s - x_t| [m];
    // NaN when no mapping was assessed.
    double coordinateRmsError = std::numeric_limits<double>::quiet_NaN();
    double coordinateMaxError = std::numeric_limits<double>::quiet_NaN();

    // One line, e.g. "max nearest distance 1.0e-03 m (0.9 % of interface size 1.1e-01 m), ...".
    std::string toString() const;
};

// Geometry only (coordinate errors stay NaN).
MappingQuality assessGeometry(const PointCloud& source, const PointCloud& target);

// Geometry + coordinate errors of a computed mapping (pre: mapping computed on source, target).
MappingQuality assessQuality(const Mapping& mapping, const PointCloud& source,
                             const PointCloud& target);

// Throws std::runtime_error (one line) when the clouds do not overlap: bounding boxes disjoint
// by more than relativeTolerance * interfaceSize, or a target point farther than
// relativeTolerance * interfaceSize from every source point. Pre: both clouds non-empty.
void checkOverlap(const PointCloud& source, const PointCloud& target, double relativeTolerance);

} // namespace fsi::mapping
