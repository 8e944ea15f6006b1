// SPDX-License-Identifier: GPL-3.0-or-later
// The solid's parameters (YAML block `solid:`), each struct parsed and validated in one
// place. Every key is documented in config/solid.example.yaml. Units SI.
#pragma once
#include "fe/Settings.hpp"
#include "linalg/SparseDirectSolver.hpp"
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"
#include "schedule/Planned.hpp"
#include "schedule/Registry.hpp"

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

// solid.newton into fe::NewtonSettings (one-line errors).
fe::NewtonSettings parseNewton(const Block& b);

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
    std::vector<fe::PrescribedDisplacement> displacements; // value per component (no field)
    std::vector<TractionLoad> tractions;
    std::vector<NodalForceLoad> forces;
    static LoadParameters parse(const Block& b);
};

// Cap of the input size: watched points of the output block.
constexpr std::size_t kMaxWatchPoints = 1000;

// Time levels of a standalone run: a schedule of the schedule layer by `type` (schedule/
// Registry.hpp: steady, uniform (the default when type is omitted), list, geometric, adaptive;
// adaptive follows change_k = max|u_k - u_{k-1}| / max|u_k| over the nodes), plus the load
// factor: loads(t) = loadFactor(t) * configured loads, piecewise linear in t. The load-factor
// corners inside (0, end) are landed on exactly by geometric/adaptive (added to their `hit`).
// No time block: one static level at t = 0 (steady).
struct TimeParameters
{
    schedule::ScheduleParameters schedule = schedule::SteadyParameters{};
    std::vector<std::array<double, 2>> loadFactor; // (t, factor), t increasing
    double factorAt(double t) const;
    // Reads the time block; an adaptive first_step of 0 becomes min(relaxationTimes) / 10.
    static TimeParameters parse(const Block& b, const std::vector<double>& relaxationTimes);
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
    fe::NewtonSettings newton;
    // solid.linear_solver: MUMPS settings (verbosity, ordering, BLR, refinement, threads);
    // defaults as documented in config/solid.example.yaml. symmetric and reuseFactorization are
    // set by fe::StructuralSolver.
    linalg::DirectSolverOptions linearSolver;
    double refactorShearDrift = 0.0; // linear_solver.refactor_shear_drift (fe::ProblemDefinition)
    LoadParameters loads;
    TimeParameters time;
    OutputParameters output;

    // Reads and validates `file`. Throws std::runtime_error (one line: file, key, fix).
    static SolidConfig load(const std::string& file);
    // The same from the already loaded document `root` of `file` (read the YAML once).
    static SolidConfig fromRoot(const Block& root, const std::string& file);
    // The resolved values as YAML (printed at start-up, written to the output folder).
    std::string echo() const;
};

material::MaterialParameters parseMaterial(const Block& b);
// The `linear_solver` block into options (defaults for absent keys); one-line errors.
linalg::DirectSolverOptions parseLinearSolver(const Block& b);

} // namespace fsi::config
