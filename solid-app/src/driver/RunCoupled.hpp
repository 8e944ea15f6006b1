// SPDX-License-Identifier: GPL-3.0-or-later
//
// solid-app's coupled mode: a config with a `coupling:` block. solid-app is the driver: it
// opens the channel to fluid-app (port server or MPMD), runs the quasi-steady loop and writes
//   OUT/config.echo.yaml      the resolved solid + coupling configuration
//   OUT/coupling.csv          one row per coupling iteration
//   OUT/history.csv           one row per accepted level (forces, watched points, angle)
//   OUT/summary.csv           totals of the run (levels, iterations, wall time split)
//   OUT/interface/level_*.csv wetted-node positions, displacements and forces per level
//   OUT/solid_*.vtu + solid.pvd  structural fields per level for ParaView
//   OUT/checkpoint/           restart files (driver/Checkpoint.hpp); restart = true continues
//                             from OUT/checkpoint/latest (same config, same OUT)
#pragma once

#include <exception>
#include <string>

namespace fsi::config
{
class Block;
}

namespace fsi::driver
{

// Removes --launch, --port-file and --comm-timeout from argc/argv and keeps them: they override
// the config's coupling.launch block. Call first in main, before other argument parsing.
void takeLaunchFlags(int& argc, char** argv);

// For main's catch block (errors outside runCoupled: arguments, an unreadable config). In an
// MPMD launch the fluid waits for this program in the MPMD split: prints the error once and
// ends the whole job at once (MPI_Abort). Otherwise returns, and main exits as usual.
void endMpmdLaunchOnError(const std::exception& error);

// Runs the coupled case of `configFile`, whose YAML document main has read once (`root`, with
// its `coupling:` block); collective over this program's ranks. Returns the exit code; errors
// end the run through fsi::comm (the fluid is told why) with a one-line message.
int runCoupled(const config::Block& root, const std::string& configFile,
               const std::string& outputFolder, bool restart = false);

} // namespace fsi::driver
