// SPDX-License-Identifier: GPL-3.0-or-later
//
// Base of the strategies whose operator H is an explicit sparse matrix (targets x sources) that
// their compute() fills (nearest-projection, moving-least-squares): an apply is one sparse
// product each way, H for displacements and H^T for forces, without allocation.
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/SparseCore>

#include <vector>

namespace fsi::mapping
{

class SparseMapping : public Mapping
{
public:
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const final
    {
        targetValues.noalias() = weights_ * sourceValues;
    }
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const final
    {
        sourceValues.noalias() = weights_.transpose() * targetValues;
    }

protected:
    // H (targets x sources) from (target, source, weight) triplets, duplicates summed; sets
    // targetSize() and sourceSize().
    void setWeights(Eigen::Index targets, Eigen::Index sources,
                    const std::vector<Eigen::Triplet<double>>& triplets)
    {
        weights_.resize(targets, sources);
        weights_.setFromTriplets(triplets.begin(), triplets.end());
        targetSize_ = targets;
        sourceSize_ = sources;
    }

private:
    Eigen::SparseMatrix<double, Eigen::RowMajor> weights_;
};

} // namespace fsi::mapping
