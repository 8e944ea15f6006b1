// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/Mapping.hpp"

#include "config/YamlReader.hpp"
#include "mapping/NearestNeighbour.hpp"
#include "mapping/Quality.hpp"
#include "mapping/TargetSmoothing.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::mapping
{

MappingParameters::MappingParameters() : strategy(NearestNeighbourParameters{}) {}

void MappingParameters::validate() const
{
    strategy.validate();
    validateOverlapTolerance();
    validateSmoothingRadius();
}

void MappingParameters::validateOverlapTolerance() const
{
    if (!(overlapTolerance > 0.0) || !std::isfinite(overlapTolerance))
        throw std::runtime_error("mapping.overlap_tolerance must be > 0 (relative to the "
                                 "interface size; e.g. 0.1), got " +
                                 config::formatNumber(overlapTolerance));
}

void MappingParameters::validateSmoothingRadius() const
{
    if (!(smoothingRadius >= 0.0) || !std::isfinite(smoothingRadius))
        throw std::runtime_error("mapping.smoothing_radius must be >= 0 m (0 = off; e.g. 2e-4, "
                                 "a few fluid wall spacings), got " +
                                 config::formatNumber(smoothingRadius));
}

std::unique_ptr<Mapping> makeMapping(const MappingParameters& params)
{
    params.validate();
    return params.strategy.make();
}

std::unique_ptr<Mapping> buildMapping(const MappingParameters& params, const PointCloud& source,
                                      const PointCloud& target, const SourceSurface* surface)
{
    return std::move(buildMappings(params, source, {&target}, surface).front());
}

std::vector<std::unique_ptr<Mapping>> buildMappings(const MappingParameters& params,
                                                    const PointCloud& source,
                                                    const std::vector<const PointCloud*>& targets,
                                                    const SourceSurface* surface)
{
    params.validate();
    std::vector<std::unique_ptr<Mapping>> mappings;
    for (const PointCloud* target : targets)
    {
        checkOverlap(source, *target, params.overlapTolerance);
        std::unique_ptr<Mapping> mapping =
            mappings.empty() ? nullptr : mappings.front()->withSameSource(*target);
        if (!mapping)
        {
            mapping = makeMapping(params);
            if (surface)
                mapping->setSourceSurface(*surface);
            mapping->compute(source, *target);
        }
        mappings.push_back(std::move(mapping));
    }
    // smoothing last: withSameSource() above needs the strategy's own first mapping
    if (params.smoothingRadius > 0.0)
        for (size_t i = 0; i < mappings.size(); ++i)
            mappings[i] = std::make_unique<SmoothedMapping>(std::move(mappings[i]), *targets[i],
                                                            params.smoothingRadius);
    return mappings;
}

} // namespace fsi::mapping
