// SPDX-License-Identifier: GPL-3.0-or-later
// solid-app's standalone mode: a structural problem under the prescribed load/time history
// of the config (no fluid). Collective on MPI_COMM_WORLD; rank 0 prints and writes.
#pragma once
#include "fe/StructuralSolver.hpp"

#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

namespace fsi::app
{

struct RunOptions
{
    std::string configFile;
    std::string outputFolder; // "" = solid.output.folder of the config
    bool restart = false;     // coupled mode: continue from OUT/checkpoint/latest
    bool help = false;        // -h / --help: print usageText() and exit 0
};

// Parses "CONFIG.yaml [--out DIR] [--restart] | --help"; throws std::runtime_error with a usage
// line. (--launch, --port-file and --comm-timeout are taken out of argv before, by the driver.)
RunOptions parseArguments(int argc, char** argv);

// The --help text: every option of solid-app, standalone and coupled.
std::string usageText();

// Runs the standalone problem of options.configFile, whose YAML document main has read once
// (`root`). Returns the exit code (0 ok, 2 a level did not converge); throws
// std::runtime_error (one line) on bad input.
int runStandalone(const config::Block& root, const RunOptions& options);

} // namespace fsi::app
