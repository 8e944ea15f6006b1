// SPDX-License-Identifier: GPL-3.0-or-later
// The accelerators by keyword: {name, keys, parse} per strategy; make() comes with the parsed
// AcceleratorParameters. A new strategy is its two files (class + parameters, see
// Accelerator.hpp for what the parameters provide) and one line in Registry.cpp.
// config/coupled.example.yaml documents each strategy's keys (a test checks them).
#pragma once

#include "acceleration/Accelerator.hpp"

#include <string>
#include <vector>

namespace fsi::acceleration
{

using AcceleratorType = config::StrategyType<Accelerator>;

// Every registered strategy, in registration order.
const std::vector<AcceleratorType>& acceleratorTypes();

// The strategy called `name`; throws std::runtime_error "acceleration.type 'x' is unknown; use
// one of ..." otherwise.
const AcceleratorType& acceleratorType(const std::string& name);

} // namespace fsi::acceleration
