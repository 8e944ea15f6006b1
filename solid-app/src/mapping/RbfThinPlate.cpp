// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfThinPlate.hpp"
#include "config/YamlReader.hpp"

#include "mapping/RbfSupport.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::mapping
{

const std::vector<std::string>& ThinPlateParameters::keys()
{
    static const std::vector<std::string> k{"max_source_points"};
    return k;
}

ThinPlateParameters ThinPlateParameters::parse(const config::Block& layer)
{
    ThinPlateParameters p;
    if (const auto b = layer.optionalBlock(keyword))
    {
        b->allowOnly(keys());
        p.maxSourcePoints = b->integer("max_source_points", static_cast<int>(p.maxSourcePoints));
    }
    return p;
}

void ThinPlateParameters::validate() const
{
    if (maxSourcePoints < 1)
        throw std::runtime_error("rbf-thin-plate.max_source_points must be >= 1 for type "
                                 "rbf-thin-plate (got " +
                                 std::to_string(maxSourcePoints) + ")");
}

std::string ThinPlateParameters::echo() const
{
    return "{max_source_points: " + std::to_string(maxSourcePoints) + "}";
}

namespace
{
inline double thinPlate(double r)
{
    return r > 0.0 ? r * r * std::log(r) : 0.0;
}

void fillKernel(const PointCloud& rows, const PointCloud& cols, Eigen::Ref<Eigen::MatrixXd> out)
{
    for (Eigen::Index j = 0; j < cols.rows(); ++j)
        for (Eigen::Index i = 0; i < rows.rows(); ++i)
            out(i, j) = thinPlate((rows.row(i) - cols.row(j)).norm());
}

void resizeWorkspace(Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols)
{
    if (m.rows() != rows || m.cols() != cols)
        m.resize(rows, cols);
}
} // namespace

void RbfThinPlate::compute(const PointCloud& source, const PointCloud& target)
{
    if (source.rows() > maxSourcePoints_)
        throw std::runtime_error("mapping rbf-thin-plate: " + std::to_string(source.rows()) +
                                 " source points exceed mapping.max_source_points " +
                                 std::to_string(maxSourcePoints_) +
                                 " (dense O(N^3) set-up); use type rbf-wendland-c2 or raise it");
    detail::checkDistinctPoints(source, "rbf-thin-plate");
    const detail::Normalisation normalisation(source);
    const PointCloud s = normalisation.apply(source), t = normalisation.apply(target);
    const detail::LinearPolynomial polynomial(s, t);
    const Eigen::Index ns = s.rows(), nt = t.rows(), r = polynomial.rank();

    Eigen::MatrixXd system = Eigen::MatrixXd::Zero(ns + r, ns + r);
    fillKernel(s, s, system.topLeftCorner(ns, ns));
    system.topRightCorner(ns, r) = polynomial.sourceBasis;
    system.bottomLeftCorner(r, ns) = polynomial.sourceBasis.transpose();
    lu_.compute(system);

    evaluation_.resize(nt, ns + r);
    fillKernel(t, s, evaluation_.leftCols(ns));
    evaluation_.rightCols(r) = polynomial.targetBasis;
    sourceSize_ = ns;
    targetSize_ = nt;
}

void RbfThinPlate::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                   Eigen::Ref<Values> targetValues) const
{
    const Eigen::Index n = lu_.rows(), k = sourceValues.cols();
    resizeWorkspace(rhs_, n, k);
    resizeWorkspace(solution_, n, k);
    rhs_.topRows(sourceSize_) = sourceValues;
    rhs_.bottomRows(n - sourceSize_).setZero();
    // Column by column: vector solves and products need no heap workspace (matrix ones do).
    for (Eigen::Index j = 0; j < k; ++j)
    {
        solution_.col(j) = lu_.solve(rhs_.col(j));
        targetValues.col(j).noalias() = evaluation_ * solution_.col(j);
    }
}

void RbfThinPlate::applyConservative(const Eigen::Ref<const Values>& targetValues,
                                     Eigen::Ref<Values> sourceValues) const
{
    const Eigen::Index n = lu_.rows(), k = targetValues.cols();
    resizeWorkspace(rhs_, n, k);
    resizeWorkspace(solution_, n, k);
    // The saddle-point matrix is symmetric: H^T = R^T A^{-1} E^T.
    for (Eigen::Index j = 0; j < k; ++j)
    {
        rhs_.col(j).noalias() = evaluation_.transpose() * targetValues.col(j);
        solution_.col(j) = lu_.solve(rhs_.col(j));
    }
    sourceValues = solution_.topRows(sourceSize_);
}

} // namespace fsi::mapping
