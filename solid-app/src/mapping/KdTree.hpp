// SPDX-License-Identifier: GPL-3.0-or-later
//
// Kd-tree over a 3-D point cloud (nanoflann behind a pimpl). Owns a copy of the points.
#pragma once

#include "mapping/Mapping.hpp"

#include <memory>
#include <utility>
#include <vector>

namespace fsi::mapping
{

class KdTree
{
public:
    explicit KdTree(const PointCloud& points); // pre: points non-empty
    ~KdTree();
    KdTree(const KdTree&) = delete;
    KdTree& operator=(const KdTree&) = delete;

    // Index of the nearest point to q (3 doubles, m); distance [m] returned in *distance.
    Eigen::Index nearest(const double* q, double* distance) const;

    // The k nearest points (k <= size), closest first: indices and distances [m].
    void nearest(const double* q, int k, std::vector<Eigen::Index>& indices,
                 std::vector<double>& distances) const;

    // All points with |p - q| <= radius [m]: (index, squared distance [m^2]), unsorted.
    void withinRadius(const double* q, double radius,
                      std::vector<std::pair<Eigen::Index, double>>& found) const;

    Eigen::Index size() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace fsi::mapping
