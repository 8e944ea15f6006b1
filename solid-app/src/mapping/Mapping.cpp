// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/Mapping.hpp"

#include "mapping/NearestNeighbour.hpp"
#include "mapping/Quality.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"

#include <cmath>
#include <stdexcept>

namespace fsi::mapping
{

void WendlandParameters::validate() const
{
    if (!(supportRadius > 0.0) || !std::isfinite(supportRadius))
        throw std::runtime_error("mapping.support_radius must be > 0 m for type rbf-wendland-c2 "
                                 "(got " + std::to_string(supportRadius) +
                                 "); set it to a few solid node spacings");
}

void ThinPlateParameters::validate() const
{
    if (maxSourcePoints < 1)
        throw std::runtime_error("mapping.max_source_points must be >= 1 for type "
                                 "rbf-thin-plate (got " + std::to_string(maxSourcePoints) + ")");
}

void MappingParameters::validate() const
{
    if (type == "rbf-wendland-c2")
        wendland.validate();
    else if (type == "rbf-thin-plate")
        thinPlate.validate();
    else if (type != "nearest-neighbour")
        throw std::runtime_error("mapping.type '" + type + "' is unknown; use one of "
                                 "nearest-neighbour, rbf-thin-plate, rbf-wendland-c2");
    if (!(overlapTolerance > 0.0) || !std::isfinite(overlapTolerance))
        throw std::runtime_error("mapping.overlap_tolerance must be > 0 (relative to the "
                                 "interface size; e.g. 0.1), got " +
                                 std::to_string(overlapTolerance));
}

std::unique_ptr<Mapping> makeMapping(const MappingParameters& params)
{
    params.validate();
    if (params.type == "rbf-thin-plate")
        return std::make_unique<RbfThinPlate>(params.thinPlate.maxSourcePoints);
    if (params.type == "rbf-wendland-c2")
        return std::make_unique<RbfWendlandC2>(params.wendland.supportRadius);
    return std::make_unique<NearestNeighbour>();
}

std::unique_ptr<Mapping> buildMapping(const MappingParameters& params, const PointCloud& source,
                                      const PointCloud& target)
{
    params.validate();
    checkOverlap(source, target, params.overlapTolerance);
    std::unique_ptr<Mapping> mapping = makeMapping(params);
    mapping->compute(source, target);
    return mapping;
}

} // namespace fsi::mapping
