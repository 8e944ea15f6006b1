// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Registry.hpp"

#include "acceleration/Aitken.hpp"
#include "acceleration/ConstantRelaxation.hpp"
#include "acceleration/IqnIls.hpp"

#include <stdexcept>

namespace fsi::acceleration
{

const std::vector<AcceleratorType>& acceleratorTypes()
{
    static const std::vector<AcceleratorType> types{
        config::strategyType<ConstantParameters, Accelerator>(),
        config::strategyType<AitkenParameters, Accelerator>(),
        config::strategyType<IqnIlsParameters, Accelerator>(),
    };
    return types;
}

const AcceleratorType& acceleratorType(const std::string& name)
{
    return config::findStrategyType(acceleratorTypes(), name);
}

} // namespace fsi::acceleration
