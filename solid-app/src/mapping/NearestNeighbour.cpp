// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/NearestNeighbour.hpp"

#include "mapping/KdTree.hpp"

namespace fsi::mapping
{

const std::vector<std::string>& NearestNeighbourParameters::keys()
{
    static const std::vector<std::string> none;
    return none;
}

NearestNeighbourParameters NearestNeighbourParameters::parse(const config::Block&)
{
    return {};
}

void NearestNeighbourParameters::validate() const {}

std::string NearestNeighbourParameters::echo() const
{
    return "{}";
}

void NearestNeighbour::compute(const PointCloud& source, const PointCloud& target)
{
    const KdTree tree(source);
    nearest_.resize(static_cast<size_t>(target.rows()));
    for (Eigen::Index t = 0; t < target.rows(); ++t)
        nearest_[static_cast<size_t>(t)] = tree.nearest(target.row(t).data(), nullptr);
    sourceSize_ = source.rows();
    targetSize_ = target.rows();
}

void NearestNeighbour::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                       Eigen::Ref<Values> targetValues) const
{
    for (Eigen::Index t = 0; t < targetSize_; ++t)
        targetValues.row(t) = sourceValues.row(nearest_[static_cast<size_t>(t)]);
}

void NearestNeighbour::applyConservative(const Eigen::Ref<const Values>& targetValues,
                                         Eigen::Ref<Values> sourceValues) const
{
    sourceValues.setZero();
    for (Eigen::Index t = 0; t < targetSize_; ++t)
        sourceValues.row(nearest_[static_cast<size_t>(t)]) += targetValues.row(t);
}

} // namespace fsi::mapping
