// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/Mapping.hpp"

#include "mapping/NearestNeighbour.hpp"
#include "mapping/Quality.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::mapping
{
namespace
{
// %g keeps small values readable in messages (1e-05, not 0.000000).
std::string number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}
} // namespace

void WendlandParameters::validate() const
{
    if (!(supportRadius > 0.0) || !std::isfinite(supportRadius))
        throw std::runtime_error("rbf-wendland-c2.support_radius must be > 0 m for type "
                                 "rbf-wendland-c2 (got " +
                                 number(supportRadius) + "); set it to a few solid node spacings");
    if (solver != "auto" && solver != "direct" && solver != "iterative")
        throw std::runtime_error("rbf-wendland-c2.solver '" + solver +
                                 "' is unknown; use auto, direct or iterative");
    if (directMaxPoints < 0)
        throw std::runtime_error("rbf-wendland-c2.direct_max_points must be >= 0 (got " +
                                 std::to_string(directMaxPoints) + "); e.g. 20000");
    if (!(iterativeTolerance > 0.0 && iterativeTolerance < 1.0))
        throw std::runtime_error("rbf-wendland-c2.iterative_tolerance must be in (0, 1) (got " +
                                 number(iterativeTolerance) + "); e.g. 1e-10");
}

void ThinPlateParameters::validate() const
{
    if (maxSourcePoints < 1)
        throw std::runtime_error("rbf-thin-plate.max_source_points must be >= 1 for type "
                                 "rbf-thin-plate (got " +
                                 std::to_string(maxSourcePoints) + ")");
}

void PartitionOfUnityParameters::validate() const
{
    if (pointsPerPatch < 4 || pointsPerPatch > 200)
        throw std::runtime_error("mapping.rbf-pu.points_per_patch must be in [4, 200] (got " +
                                 std::to_string(pointsPerPatch) + "); e.g. 20");
    if (!(centreSpacing > 0.0 && centreSpacing < 1.0))
        throw std::runtime_error("mapping.rbf-pu.centre_spacing must be in (0, 1) (got " +
                                 number(centreSpacing) + "); e.g. 0.85");
}

void MappingParameters::validate() const
{
    if (type == "rbf-wendland-c2")
        wendland.validate();
    else if (type == "rbf-thin-plate")
        thinPlate.validate();
    else if (type == "rbf-pu")
        partitionOfUnity.validate();
    else if (type != "nearest-neighbour")
        throw std::runtime_error("mapping.type '" + type +
                                 "' is unknown; use one of "
                                 "nearest-neighbour, rbf-thin-plate, rbf-wendland-c2, rbf-pu");
    if (!(overlapTolerance > 0.0) || !std::isfinite(overlapTolerance))
        throw std::runtime_error("mapping.overlap_tolerance must be > 0 (relative to the "
                                 "interface size; e.g. 0.1), got " +
                                 number(overlapTolerance));
}

std::unique_ptr<Mapping> makeMapping(const MappingParameters& params)
{
    params.validate();
    if (params.type == "rbf-thin-plate")
        return std::make_unique<RbfThinPlate>(params.thinPlate.maxSourcePoints);
    if (params.type == "rbf-wendland-c2")
        return std::make_unique<RbfWendlandC2>(params.wendland);
    if (params.type == "rbf-pu")
        return std::make_unique<RbfPartitionOfUnity>(params.partitionOfUnity);
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
