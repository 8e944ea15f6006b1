// SPDX-License-Identifier: GPL-3.0-or-later
//
// Target-side smoothing of a mapping (mapping.smoothing_radius R > 0): H becomes S H, where S
// (N_t x N_t) is a moving-least-squares smoother on the target cloud. Row t of S gives, at x_t,
// the value of the linear field a + B (x - x_t) fitted by weighted least squares to the values at
// the target points within R of x_t (weights (1 - (r/R)^2)^2; where those points span fewer than
// three dimensions, e.g. on a flat patch, the fit is the minimum-norm one). So:
//   - S reproduces every linear field exactly, and its rows sum to one;
//   - conservative: H^T S^T keeps the total force and, where H conserved it, the total moment
//     (sum_t S_tj x_t = x_j);
//   - it removes what varies on a scale below R between neighbouring target points, e.g. the
//     kink that a closest-point map leaves where a fine fluid surface cuts a solid edge
//     (cases/hydrofoil/README.md: the boundary-layer mesh's tip cells); a target point with no
//     other target point within R keeps its value.
// Cost: one kd-tree search and a 4 x 4 eigen-decomposition per target point at set-up; an apply
// adds one sparse product.
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/SparseCore>

#include <memory>

namespace fsi::mapping
{

using SmoothingOperator = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// S for `points` and radius [m] > 0 (throws std::runtime_error otherwise).
SmoothingOperator movingLeastSquaresSmoother(const PointCloud& points, double radius);

// S H around a computed mapping H (owned). name() is the inner strategy's.
class SmoothedMapping final : public Mapping
{
public:
    // Pre: inner computed for `target`; radius > 0.
    SmoothedMapping(std::unique_ptr<Mapping> inner, const PointCloud& target, double radius);
    std::string name() const override { return inner_->name(); }
    void compute(const PointCloud& source, const PointCloud& target) override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;
    const SmoothingOperator& smoother() const { return smoother_; }

private:
    std::unique_ptr<Mapping> inner_;
    double radius_;
    SmoothingOperator smoother_;
    mutable Values work_; // target-sized workspace, resized only when the column count changes
};

} // namespace fsi::mapping
