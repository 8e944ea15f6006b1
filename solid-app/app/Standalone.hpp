// SPDX-License-Identifier: GPL-3.0-or-later
// solid-app's standalone mode: a structural problem under the prescribed load/time history
// of the config (no fluid). Collective on MPI_COMM_WORLD; rank 0 prints and writes.
#pragma once
#include "fe/StructuralSolver.hpp"

#include <string>
#include <vector>

namespace fsi::config
{
struct SolidConfig;
}
namespace fsi::mesh
{
struct Mesh;
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

// True if the config has a top-level `coupling:` block (the driver's coupled mode).
bool isCoupledConfig(const std::string& configFile);

// The structural problem (constraints, loads, Newton settings) of a config; shared with the
// coupled mode so both build the solid the same way.
fe::ProblemDefinition problemFromConfig(const config::SolidConfig& config);
// Every surface group the config names (clamped, wetted, loaded): they must exist in the mesh.
std::vector<std::string> surfacesOf(const config::SolidConfig& config);

// Creates the output folder. A fresh run (restart == false) then removes what an earlier run of
// solid-app left there: config.echo.yaml, solid.pvd, solid_NNNNN.vtu, history.csv, levels.csv,
// summary.csv, coupling.csv, interface/ and checkpoint/; other files are kept. Call it only once
// the start has succeeded (input read; coupled: the fluid connected), so that a failed start
// leaves the folder, and its restart point, untouched. Throws a one-line error naming the path.
void prepareOutputFolder(const std::string& folder, bool restart);

// Throws (one line naming the config, the watch entry and the distance) if a watched point of
// solid.output.watch is farther from every mesh node than 10 % of the mesh's bounding-box
// diagonal: it would silently snap to a node far away (a typo, or other units).
void checkWatchPoints(const config::SolidConfig& config, const mesh::Mesh& mesh);

// Runs the standalone problem. Returns the exit code (0 ok, 2 a level did not converge);
// throws std::runtime_error (one line) on bad input.
int runStandalone(const RunOptions& options);

} // namespace fsi::app
