// SPDX-License-Identifier: GPL-3.0-or-later
// What both run modes of solid-app (standalone, coupled) share to set up a solid run from a
// validated config: the structural problem, the surface groups the mesh must have, the output
// folder and the watch-point check. Used by app/ and driver/, so that the driver does not reach
// into the application.
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

namespace fsi::setup
{

// The structural problem (constraints, loads, Newton and linear-solver settings) of a config.
fe::ProblemDefinition problemFromConfig(const config::SolidConfig& config);

// Every surface group the config names (clamped, wetted, loaded): they must exist in the mesh.
std::vector<std::string> surfaceGroups(const config::SolidConfig& config);

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

} // namespace fsi::setup
