// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/Registry.hpp"

#include "material/LinearElastic.hpp"
#include "material/NeoHookean.hpp"
#include "material/Viscoelastic.hpp"

namespace fsi::material
{

const std::vector<MaterialType>& materialTypes()
{
    static const std::vector<MaterialType> types{
        LinearElastic::entry(),
        NeoHookean::entry(),
        Viscoelastic::entry(),
    };
    return types;
}

const MaterialType* findMaterialType(const std::string& name)
{
    for (const auto& t : materialTypes())
        if (t.name == name)
            return &t;
    return nullptr;
}

std::string materialTypeList()
{
    const auto& types = materialTypes();
    std::string list;
    for (std::size_t i = 0; i < types.size(); ++i)
        list += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + types[i].name;
    return list;
}

} // namespace fsi::material
