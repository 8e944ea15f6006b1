// SPDX-License-Identifier: GPL-3.0-or-later
//
// nearest-neighbour: each target point takes the value of its nearest source point (kd-tree).
// H has one 1 per row. Consistent: first order in the spacing; reproduces constants only, so
// the conservative map keeps total force but not total moment (the force moves from the face
// centre to the nearest node: the moment changes by sum (x_s - x_t) x f_t).
#pragma once

#include "mapping/Mapping.hpp"

#include <vector>

namespace fsi::mapping
{

class NearestNeighbour;

// nearest-neighbour has no coefficients (no block).
struct NearestNeighbourParameters
{
    static constexpr const char* keyword = "nearest-neighbour";
    using Strategy = NearestNeighbour;
    static const std::vector<std::string>& keys();
    static NearestNeighbourParameters parse(const config::Block& layer); // nothing to read
    void validate() const;
    std::string echo() const;
};

class NearestNeighbour final : public Mapping
{
public:
    NearestNeighbour() = default;
    explicit NearestNeighbour(const NearestNeighbourParameters&) {}
    std::string name() const override { return "nearest-neighbour"; }
    void compute(const PointCloud& source, const PointCloud& target) override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;

    // Source index used by each target point.
    const std::vector<Eigen::Index>& nearestSource() const { return nearest_; }

private:
    std::vector<Eigen::Index> nearest_;
};

} // namespace fsi::mapping
