// SPDX-License-Identifier: GPL-3.0-or-later
// Checks shared by the strategies' validate(): one-line std::runtime_error naming
// acceleration.<key>, the value and the fix.
#pragma once

#include "config/YamlReader.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::acceleration
{

// A coefficient for messages: "unset" for NaN (a required key not given).
inline std::string valueText(double x)
{
    return std::isnan(x) ? std::string("unset") : config::formatNumber(x);
}

inline void checkInitialRelaxation(double omega, const char* key)
{
    if (!(omega > 0.0 && omega <= 1.0))
        throw std::runtime_error(std::string("acceleration.") + key + " must be in (0, 1] (got " +
                                 valueText(omega) +
                                 "); set it, e.g. 0.5, smaller for strong coupling");
}

} // namespace fsi::acceleration
