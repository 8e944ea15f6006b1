// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/TargetSmoothing.hpp"

#include "mapping/KdTree.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fsi::mapping
{

SmoothingOperator movingLeastSquaresSmoother(const PointCloud& points, double radius)
{
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw std::runtime_error("mapping.smoothing_radius must be > 0 m here, got " +
                                 std::to_string(radius));
    const Eigen::Index n = points.rows();
    SmoothingOperator S(n, n);
    if (n == 0)
        return S;
    const KdTree tree(points);
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<std::pair<Eigen::Index, double>> found;
    Eigen::MatrixXd A; // rows [1, (x_j - x_t) / R]
    Eigen::VectorXd w; // weights
    for (Eigen::Index t = 0; t < n; ++t)
    {
        tree.withinRadius(points.row(t).data(), radius, found);
        const Eigen::Index m = static_cast<Eigen::Index>(found.size());
        if (m <= 1)
        {
            triplets.emplace_back(t, t, 1.0);
            continue;
        }
        A.resize(m, 4);
        w.resize(m);
        for (Eigen::Index k = 0; k < m; ++k)
        {
            const Eigen::Index j = found[static_cast<size_t>(k)].first;
            A(k, 0) = 1.0;
            A.block<1, 3>(k, 1) = (points.row(j) - points.row(t)) / radius;
            const double q = 1.0 - found[static_cast<size_t>(k)].second / (radius * radius);
            w(k) = q > 0.0 ? q * q : 0.0;
        }
        const Eigen::Matrix4d M = A.transpose() * w.asDiagonal() * A;
        // minimum-norm fit: the pseudo-inverse, directions with a tiny eigenvalue dropped (the
        // normal of a flat patch, the cross-directions of a line of points)
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(M);
        const Eigen::Vector4d lambda = eigen.eigenvalues();
        const double cutoff = 1e-10 * lambda.cwiseAbs().maxCoeff();
        Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
        for (int i = 0; i < 4; ++i)
            if (lambda(i) > cutoff)
                inverse(i) = 1.0 / lambda(i);
        const Eigen::Matrix4d Mplus =
            eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
        // the fitted value at x_t: e_1^T M^+ A^T W f
        const Eigen::RowVectorXd row = Mplus.row(0) * A.transpose() * w.asDiagonal();
        for (Eigen::Index k = 0; k < m; ++k)
            if (row(k) != 0.0)
                triplets.emplace_back(t, found[static_cast<size_t>(k)].first, row(k));
    }
    S.setFromTriplets(triplets.begin(), triplets.end());
    return S;
}

SmoothedMapping::SmoothedMapping(std::unique_ptr<Mapping> inner, const PointCloud& target,
                                 double radius)
    : inner_(std::move(inner)), radius_(radius),
      smoother_(movingLeastSquaresSmoother(target, radius))
{
    if (!inner_ || inner_->targetSize() != target.rows())
        throw std::logic_error(
            "SmoothedMapping: the inner mapping must be computed for the target");
    sourceSize_ = inner_->sourceSize();
    targetSize_ = inner_->targetSize();
}

void SmoothedMapping::compute(const PointCloud& source, const PointCloud& target)
{
    inner_->compute(source, target);
    smoother_ = movingLeastSquaresSmoother(target, radius_);
    sourceSize_ = inner_->sourceSize();
    targetSize_ = inner_->targetSize();
}

void SmoothedMapping::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                      Eigen::Ref<Values> targetValues) const
{
    if (work_.rows() != targetSize_ || work_.cols() != sourceValues.cols())
        work_.resize(targetSize_, sourceValues.cols());
    inner_->applyConsistent(sourceValues, work_);
    targetValues.noalias() = smoother_ * work_;
}

void SmoothedMapping::applyConservative(const Eigen::Ref<const Values>& targetValues,
                                        Eigen::Ref<Values> sourceValues) const
{
    if (work_.rows() != targetSize_ || work_.cols() != targetValues.cols())
        work_.resize(targetSize_, targetValues.cols());
    work_.noalias() = smoother_.transpose() * targetValues;
    inner_->applyConservative(work_, sourceValues);
}

} // namespace fsi::mapping
