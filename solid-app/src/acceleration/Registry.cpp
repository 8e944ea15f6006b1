// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/Registry.hpp"

#include "acceleration/Aitken.hpp"
#include "acceleration/ConstantRelaxation.hpp"
#include "acceleration/IqnIls.hpp"

#include <stdexcept>

namespace fsi::acceleration
{

namespace
{
template <class P> AcceleratorType entry()
{
    return {P::keyword, P::keys(),
            [](const config::Block& b) { return AcceleratorParameters(P::parse(b)); }};
}
} // namespace

const std::vector<AcceleratorType>& acceleratorTypes()
{
    static const std::vector<AcceleratorType> types{
        entry<ConstantParameters>(),
        entry<AitkenParameters>(),
        entry<IqnIlsParameters>(),
    };
    return types;
}

const AcceleratorType& acceleratorType(const std::string& name)
{
    for (const auto& t : acceleratorTypes())
        if (t.name == name)
            return t;
    throw std::runtime_error("acceleration.type '" + name + "' is unknown; use one of " +
                             acceleratorTypeList());
}

std::string acceleratorTypeList()
{
    std::string list;
    for (const auto& t : acceleratorTypes())
        list += (list.empty() ? "" : ", ") + t.name;
    return list;
}

} // namespace fsi::acceleration
