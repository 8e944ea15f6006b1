// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfSupport.hpp"

#include "mapping/KdTree.hpp"

#include <Eigen/SVD>

#include <stdexcept>
#include <string>

namespace fsi::mapping::detail
{

Normalisation::Normalisation(const PointCloud& source)
{
    const Eigen::RowVector3d lo = source.colwise().minCoeff(), hi = source.colwise().maxCoeff();
    centre = 0.5 * (lo + hi);
    scale = (hi - lo).maxCoeff();
    if (!(scale > 0.0))
        scale = 1.0; // a single point: nothing to scale
}

PointCloud Normalisation::apply(const PointCloud& points) const
{
    return (points.rowwise() - centre) / scale;
}

namespace
{
Eigen::MatrixXd linearBasis(const PointCloud& p)
{
    Eigen::MatrixXd basis(p.rows(), 4);
    basis.col(0).setOnes();
    basis.rightCols(3) = p;
    return basis;
}
} // namespace

LinearPolynomial::LinearPolynomial(const PointCloud& sourceNormalised,
                                   const PointCloud& targetNormalised)
{
    const Eigen::MatrixXd ps = linearBasis(sourceNormalised);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(ps, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = svd.singularValues();
    Eigen::Index r = 0;
    while (r < s.size() && s(r) > 1e-6 * s(0))
        ++r;
    sourceBasis = svd.matrixU().leftCols(r);
    const Eigen::MatrixXd transform =
        svd.matrixV().leftCols(r) * s.head(r).cwiseInverse().asDiagonal();
    targetBasis = linearBasis(targetNormalised) * transform;
}

void checkDistinctPoints(const PointCloud& source, const char* mappingName)
{
    if (source.rows() < 2)
        return;
    KdTree tree(source);
    const double size = (source.colwise().maxCoeff() - source.colwise().minCoeff()).norm();
    std::vector<Eigen::Index> index;
    std::vector<double> distance;
    for (Eigen::Index i = 0; i < source.rows(); ++i)
    {
        tree.nearest(source.row(i).data(), 2, index, distance);
        if (distance[1] <= 1e-12 * size)
        {
            const Eigen::Index j = index[0] == i ? index[1] : index[0];
            throw std::runtime_error(std::string("mapping ") + mappingName + ": source points " +
                                     std::to_string(i) + " and " + std::to_string(j) +
                                     " coincide; merge duplicate wetted nodes or use type "
                                     "nearest-neighbour");
        }
    }
}

} // namespace fsi::mapping::detail
