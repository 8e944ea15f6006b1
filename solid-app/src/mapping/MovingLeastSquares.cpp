// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/MovingLeastSquares.hpp"

#include "config/YamlReader.hpp"
#include "mapping/KdTree.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fsi::mapping
{

const std::vector<std::string>& MovingLeastSquaresParameters::keys()
{
    static const std::vector<std::string> k{"neighbours", "radius_factor", "cutoff"};
    return k;
}

MovingLeastSquaresParameters MovingLeastSquaresParameters::parse(const config::Block& layer)
{
    MovingLeastSquaresParameters p;
    if (const auto b = layer.optionalBlock(keyword))
    {
        b->allowOnly(keys());
        p.neighbours = b->integer("neighbours", p.neighbours);
        p.radiusFactor = b->number("radius_factor", p.radiusFactor);
        p.cutoff = b->number("cutoff", p.cutoff);
    }
    return p;
}

void MovingLeastSquaresParameters::validate() const
{
    std::ostringstream message;
    if (neighbours < 4 || neighbours > 100)
        message << "moving-least-squares.neighbours must be in [4, 100] (got " << neighbours
                << "); e.g. 12: a linear fit needs 4 nodes, more smooth over a wider stencil";
    else if (!(radiusFactor >= 1.05 && radiusFactor <= 5.0))
        message << "moving-least-squares.radius_factor must be in [1.05, 5] (got " << radiusFactor
                << "); e.g. 1.5 (the stencil's radius over the distance to its neighbours-th node)";
    else if (!(cutoff > 0.0 && cutoff <= 0.5))
        message << "moving-least-squares.cutoff must be in (0, 0.5] (got " << cutoff
                << "); e.g. 1e-2 (singular values below it times the largest are left out)";
    if (!message.str().empty())
        throw std::runtime_error(message.str());
}

std::string MovingLeastSquaresParameters::echo() const
{
    std::ostringstream out;
    out << "{neighbours: " << neighbours << ", radius_factor: " << radiusFactor
        << ", cutoff: " << cutoff << "}";
    return out.str();
}

MovingLeastSquares::MovingLeastSquares(const MovingLeastSquaresParameters& params) : params_(params)
{
    params_.validate();
}

void MovingLeastSquares::compute(const PointCloud& source, const PointCloud& target)
{
    const Eigen::Index n = source.rows();
    if (n < 4)
        throw std::runtime_error("mapping moving-least-squares: " + std::to_string(n) +
                                 " source points; a linear fit needs at least 4");
    const KdTree tree(source);
    const int k = static_cast<int>(std::min<Eigen::Index>(params_.neighbours, n));
    const int kMax = static_cast<int>(std::min<Eigen::Index>(4 * params_.neighbours, n));
    std::vector<Eigen::Index> index;
    std::vector<double> distance;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(target.rows()) * static_cast<size_t>(kMax));
    Eigen::MatrixXd A(kMax, 4); // sqrt(w) [1, (x_j - c) / R]
    Eigen::VectorXd sqrtW(kMax);
    maxGap_ = 0.0;
    for (Eigen::Index t = 0; t < target.rows(); ++t)
    {
        const Eigen::RowVector3d x = target.row(t);
        tree.nearest(x.data(), kMax, index, distance);
        maxGap_ = std::max(maxGap_, distance[0]);
        double radius = params_.radiusFactor * distance[static_cast<size_t>(k - 1)];
        if (kMax < n)
            radius = std::min(radius, distance[static_cast<size_t>(kMax - 1)]);
        if (!(radius > 0.0)) // k source nodes on the target itself (duplicates): take that value
        {
            triplets.emplace_back(t, index[0], 1.0);
            continue;
        }
        double weightSum = 0.0;
        Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
        for (int j = 0; j < kMax; ++j)
        {
            const double s = distance[static_cast<size_t>(j)] / radius;
            const double q = std::max(0.0, 1.0 - s * s);
            sqrtW(j) = q; // sqrt((1 - s^2)^2)
            weightSum += q * q;
            centre += q * q * source.row(index[static_cast<size_t>(j)]);
        }
        centre /= weightSum;
        for (int j = 0; j < kMax; ++j)
        {
            A(j, 0) = sqrtW(j);
            A.block<1, 3>(j, 1) =
                sqrtW(j) * (source.row(index[static_cast<size_t>(j)]) - centre) / radius;
        }
        // minimum-norm fit: A^+ with the directions below cutoff * sigma_max left out
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
        const Eigen::VectorXd sigma = svd.singularValues();
        Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
        for (int i = 0; i < 4; ++i)
            if (sigma(i) > params_.cutoff * sigma(0))
                inverse(i) = 1.0 / sigma(i);
        // the fitted value at x: [1, (x - c) / R] A^+ sqrt(W) f
        Eigen::RowVector4d basis;
        basis << 1.0, (x - centre) / radius;
        const Eigen::RowVectorXd row =
            (basis * svd.matrixV() * inverse.asDiagonal()) * svd.matrixU().transpose();
        for (int j = 0; j < kMax; ++j)
        {
            const double coefficient = row(j) * sqrtW(j);
            if (coefficient != 0.0)
                triplets.emplace_back(t, index[static_cast<size_t>(j)], coefficient);
        }
    }
    setWeights(target.rows(), n, triplets);
}

} // namespace fsi::mapping
