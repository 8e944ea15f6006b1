// SPDX-License-Identifier: GPL-3.0-or-later
// The solid's parameters (YAML block `solid:`), each struct parsed and validated in one
// place. Every key is documented in config/solid.example.yaml. Units SI.
#pragma once
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace fsi::config
{

class Block;

struct MeshParameters
{
    std::string file;                 // resolved against the config file's folder
    std::string volume;               // volume physical group
    std::vector<std::string> clamped; // surface groups with all dofs fixed
    std::string wetted;               // interface surface group ("" = none)
    static MeshParameters parse(const Block& b, const std::string& configDir);
};

struct NewtonParameters
{
    int maxIterations = 25;
    double residualTolerance = 1e-8;  // relative to the reference force norm
    double absoluteTolerance = 1e-10; // [N]
    bool lineSearch = true;
    int maxLoadCuts = 6; // load sub-stepping: halve up to this many times
    static NewtonParameters parse(const Block& b);
};

struct DisplacementLoad
{
    std::string surface;
    std::array<std::optional<double>, 3> value; // [m] per component (unset = free)
};

struct TractionLoad
{
    std::string surface;
    std::array<double, 3> traction{}; // [Pa] on the reference area (dead load)
};

struct NodalForceLoad
{
    std::string surface;
    std::array<double, 3> total{}; // [N], split over the surface nodes by area
};

struct LoadParameters
{
    std::array<double, 3> gravity{}; // [m/s^2], needs solid.material.density
    bool hasGravity = false;
    std::vector<DisplacementLoad> displacements;
    std::vector<TractionLoad> tractions;
    std::vector<NodalForceLoad> forces;
    static LoadParameters parse(const Block& b);
};

// Time levels t_0 = 0 (dt = 0, instantaneous) and t_n = t_{n-1} + dt ... up to `end`.
// loads(t) = loadFactor(t) * configured loads; loadFactor piecewise linear in t.
struct TimeParameters
{
    bool present = false; // no time block: one static level at t = 0
    double dt = 0.0;
    double end = 0.0;
    std::vector<std::array<double, 2>> loadFactor; // (t, factor), t increasing
    double factorAt(double t) const;
    std::vector<double> levels() const; // t_0 = 0, t_1, ...
    static TimeParameters parse(const Block& b);
};

struct WatchPoint
{
    std::string name;
    std::array<double, 3> point{};
};

struct OutputParameters
{
    std::string folder = "output";
    bool vtu = true;
    bool binary = true;
    int every = 1;
    std::vector<WatchPoint> watch;
    static OutputParameters parse(const Block& b, const std::string& configDir);
};

struct SolidConfig
{
    std::string file;
    MeshParameters mesh;
    material::MaterialParameters material;
    double density = 0.0; // [kg/m^3]
    material::Kinematics kinematics = material::Kinematics::SmallStrain;
    // solid.element.type: "displacement" (default) | "projected-dilatation" (B-bar / F-bar
    // hexahedra that do not lock for nu -> 0.5; fe::formulationFromName()).
    std::string elementType = "displacement";
    NewtonParameters newton;
    int solverVerbosity = 0;
    LoadParameters loads;
    TimeParameters time;
    OutputParameters output;
    bool hasCoupling = false; // top-level `coupling:` block present (driver)

    // Reads and validates `file`. Throws std::runtime_error (one line: file, key, fix).
    static SolidConfig load(const std::string& file);
    // The resolved values as YAML (printed at start-up, written to the output folder).
    std::string echo() const;
};

material::MaterialParameters parseMaterial(const Block& b);

} // namespace fsi::config
