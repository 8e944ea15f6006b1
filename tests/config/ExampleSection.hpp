// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: the lines of one top-level block of a shipped example config, for the tests that
// check the documented keys against the registries. Needs FSI_SOURCE_DIR (the source tree).
#pragma once

#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

namespace fsi::testing
{

// The lines under "  <section>:" of config/<file>, up to the next key at that indentation
// (comments included, the section line itself excluded). Throws when the file or the section
// is missing.
inline std::vector<std::string> exampleSection(const std::string& file, const std::string& section)
{
    std::ifstream in(std::string(FSI_SOURCE_DIR) + "/config/" + file);
    if (!in)
        throw std::runtime_error("cannot read config/" + file);
    const std::regex start("^  " + section + ":.*"), end("^  [a-z_]+:.*");
    std::vector<std::string> lines;
    bool inside = false;
    for (std::string line; std::getline(in, line);)
    {
        if (!inside)
        {
            inside = std::regex_match(line, start);
            continue;
        }
        if (std::regex_match(line, end))
            break;
        lines.push_back(line);
    }
    if (!inside)
        throw std::runtime_error("config/" + file + " has no section '" + section + "'");
    return lines;
}

} // namespace fsi::testing
