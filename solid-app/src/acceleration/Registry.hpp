// SPDX-License-Identifier: GPL-3.0-or-later
// The accelerators by keyword: {name, keys, parse} per strategy; make() comes with the parsed
// AcceleratorParameters. A new strategy is its two files (class + parameters, see
// Accelerator.hpp for what the parameters provide) and one line in Registry.cpp.
// config/coupled.example.yaml documents each strategy's keys (a test checks them).
#pragma once

#include "acceleration/Accelerator.hpp"

#include <functional>
#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

namespace fsi::acceleration
{

struct AcceleratorType
{
    std::string name;              // acceleration.type and the name of its coefficient block
    std::vector<std::string> keys; // the keys its coefficient block accepts
    // Reads the coefficient block (defaults for absent keys; not yet validated).
    std::function<AcceleratorParameters(const config::Block& coefficients)> parse;
};

// Every registered strategy, in registration order.
const std::vector<AcceleratorType>& acceleratorTypes();

// The strategy called `name`; throws std::runtime_error "acceleration.type 'x' is unknown; use
// one of ..." otherwise.
const AcceleratorType& acceleratorType(const std::string& name);

// "constant, aitken, iqn-ils" (for messages).
std::string acceleratorTypeList();

} // namespace fsi::acceleration
