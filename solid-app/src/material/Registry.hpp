// SPDX-License-Identifier: GPL-3.0-or-later
// The constitutive laws by keyword (`solid.material.type`): {name, keys, parse, validate, make}
// per law. Each law owns its entry, next to its class (`static MaterialType entry()`); a new
// law is its two files and one line in Registry.cpp. config/solid.example.yaml documents every
// law's keys (a test checks them against this registry).
#pragma once

#include "material/Material.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

namespace fsi::material
{

struct MaterialType
{
    std::string name;                  // the `type:` keyword
    std::vector<std::string> keys;     // keys of the material block the law reads, besides `type`
    bool needsTotalLagrangian = false; // rejected with small-strain kinematics
    // Reads the law's keys from the material block into p (p.type, p.file, p.keyPrefix set by
    // the caller). Does not validate.
    std::function<void(const config::Block& block, MaterialParameters& p)> parse;
    // The law's own checks, after the common ones of MaterialParameters::validate(); throws
    // std::runtime_error naming <file>: <keyPrefix>.<key>.
    std::function<void(const MaterialParameters& p)> validate;
    // The law from validated parameters.
    std::function<std::unique_ptr<Material>(const MaterialParameters& p)> make;
};

// Every registered law, in registration order.
const std::vector<MaterialType>& materialTypes();
// The law called `name`, nullptr if none is.
const MaterialType* findMaterialType(const std::string& name);
// "a, b or c": the registered keywords, for messages.
std::string materialTypeList();

} // namespace fsi::material
