// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/Registry.hpp"

#include "mapping/MovingLeastSquares.hpp"
#include "mapping/NearestNeighbour.hpp"
#include "mapping/NearestProjection.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"

namespace fsi::mapping
{

const std::vector<MappingType>& mappingTypes()
{
    static const std::vector<MappingType> types{
        config::strategyType<NearestNeighbourParameters, Mapping>(),
        config::strategyType<ThinPlateParameters, Mapping>(),
        config::strategyType<WendlandParameters, Mapping>(),
        config::strategyType<PartitionOfUnityParameters, Mapping>(),
        config::strategyType<NearestProjectionParameters, Mapping>(),
        config::strategyType<MovingLeastSquaresParameters, Mapping>(),
    };
    return types;
}

const MappingType& mappingType(const std::string& name)
{
    return config::findStrategyType(mappingTypes(), name);
}

} // namespace fsi::mapping
