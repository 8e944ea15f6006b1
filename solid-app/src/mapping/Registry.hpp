// SPDX-License-Identifier: GPL-3.0-or-later
// The mappings by keyword: {name, keys, parse} per strategy; make() comes with the parsed
// config::Strategy<Mapping>. A new mapping is its two files (class + parameters, see
// config/Strategy.hpp) and one line in Registry.cpp. config/coupled.example.yaml documents each
// strategy's keys (a test checks them).
#pragma once

#include "mapping/Mapping.hpp"

#include <string>
#include <vector>

namespace fsi::mapping
{

using MappingType = config::StrategyType<Mapping>;

// Every registered mapping, in registration order.
const std::vector<MappingType>& mappingTypes();

// The mapping called `name`; throws std::runtime_error "mapping.type 'x' is unknown; use one
// of ..." otherwise.
const MappingType& mappingType(const std::string& name);

} // namespace fsi::mapping
