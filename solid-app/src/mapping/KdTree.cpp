// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/KdTree.hpp"

#include <nanoflann.hpp>

#include <cmath>
#include <stdexcept>

namespace fsi::mapping
{

namespace
{
// nanoflann data-set adaptor over a row-major N x 3 matrix.
struct CloudAdaptor
{
    const PointCloud* points;
    size_t kdtree_get_point_count() const { return static_cast<size_t>(points->rows()); }
    double kdtree_get_pt(size_t i, size_t dim) const
    {
        return (*points)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(dim));
    }
    template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
                                                 CloudAdaptor, 3, Eigen::Index>;
} // namespace

struct KdTree::Impl
{
    PointCloud points;
    CloudAdaptor adaptor;
    std::unique_ptr<Tree> tree;
};

KdTree::KdTree(const PointCloud& points) : impl_(std::make_unique<Impl>())
{
    if (points.rows() == 0)
        throw std::runtime_error("mapping: kd-tree of an empty point cloud");
    impl_->points = points;
    impl_->adaptor.points = &impl_->points;
    impl_->tree =
        std::make_unique<Tree>(3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

KdTree::~KdTree() = default;

Eigen::Index KdTree::size() const
{
    return impl_->points.rows();
}

Eigen::Index KdTree::nearest(const double* q, double* distance) const
{
    Eigen::Index index = 0;
    double d2 = 0.0;
    nanoflann::KNNResultSet<double, Eigen::Index> result(1);
    result.init(&index, &d2);
    impl_->tree->findNeighbors(result, q, nanoflann::SearchParams());
    if (distance)
        *distance = std::sqrt(d2);
    return index;
}

void KdTree::nearest(const double* q, int k, std::vector<Eigen::Index>& indices,
                     std::vector<double>& distances) const
{
    indices.resize(static_cast<size_t>(k));
    distances.resize(static_cast<size_t>(k));
    nanoflann::KNNResultSet<double, Eigen::Index> result(static_cast<Eigen::Index>(k));
    result.init(indices.data(), distances.data());
    impl_->tree->findNeighbors(result, q, nanoflann::SearchParams());
    for (double& d : distances)
        d = std::sqrt(d);
}

void KdTree::withinRadius(const double* q, double radius,
                          std::vector<std::pair<Eigen::Index, double>>& found) const
{
    found.clear();
    nanoflann::SearchParams params;
    params.sorted = false;
    impl_->tree->radiusSearch(q, radius * radius, found, params);
}

} // namespace fsi::mapping
