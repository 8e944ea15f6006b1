// SPDX-License-Identifier: GPL-3.0-or-later
// Numbers in the acceleration layer's messages: %g keeps small values (1e-07, not 0.000000).
#pragma once

#include <cstdio>
#include <string>

namespace fsi::acceleration
{

inline std::string numberText(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

} // namespace fsi::acceleration
