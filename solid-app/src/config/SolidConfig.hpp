// SPDX-License-Identifier: GPL-3.0-or-later
// The solid's parameters (YAML block `solid:`), each struct parsed and validated in one
// place. Every key is documented in config/solid.example.yaml. Units SI.
#pragma once
#include "fe/Settings.hpp"
#include "linalg/SparseDirectSolver.hpp"
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

// Caps of the input size: levels of a time block, watched points of the output block.
constexpr long kMaxTimeLevels = 1000000;
constexpr std::size_t kMaxWatchPoints = 1000;

// Time levels of a standalone run: t_0 = 0 (dt = 0, instantaneous), then by `type`:
//   uniform    t_n = n dt up to end (the default when type is omitted)
//   list       the given times (strictly increasing, first 0)
//   geometric  t_1 = first_step, dt_{k+1} = growth dt_k (capped at max_step) up to end
//   adaptive   dt_{k+1} = dt_k clamp(target_change / change_k, shrink_limit, growth_limit) within
//              [min_step, max_step], change_k = max|u_k - u_{k-1}| / max|u_k| over the nodes;
//              first_step 0 = a tenth of the shortest Prony time
// geometric/adaptive land exactly on `end`, on the `hit` times and on the load_factor corners.
// loads(t) = loadFactor(t) * configured loads; loadFactor piecewise linear in t.
struct TimeParameters
{
    bool present = false;         // no time block: one static level at t = 0
    std::string type = "uniform"; // uniform | list | geometric | adaptive
    double dt = 0.0;              // uniform [s]
    double end = 0.0;             // uniform, geometric, adaptive [s]
    std::vector<double> times;    // list [s]
    double firstStep = 0.0;       // geometric (> 0), adaptive (0: min tau / 10) [s]
    double growth = 1.5;          // geometric
    double maxStep = 0.0;         // geometric, adaptive [s]; 0 = unlimited
    double minStep = 0.0;         // adaptive [s]
    double targetChange = 0.02;   // adaptive
    double growthLimit = 2.0;     // adaptive
    double shrinkLimit = 0.5;     // adaptive
    std::vector<double> hit;      // geometric, adaptive: times to land on [s]
    std::vector<std::array<double, 2>> loadFactor; // (t, factor), t increasing
    double factorAt(double t) const;
    // All level times t_0 = 0, t_1, ... for uniform, list and geometric (and {0} without a time
    // block); adaptive: empty (the times follow the solution, see nextStep()).
    std::vector<double> levels() const;
    // The times a geometric/adaptive schedule lands on exactly, sorted, in (0, end].
    std::vector<double> marks() const;
    // Next level time after `time` for geometric/adaptive: `step` [s] shortened to land on the
    // next mark (and stretched to it when less than a fifth of a step would be left).
    double nextTime(double time, double step) const;
    // Adaptive: the step after one of `lastStep` [s] whose relative change was `change` [-].
    double nextStep(double lastStep, double change) const;
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
    fe::NewtonSettings newton;
    // solid.linear_solver: MUMPS settings (verbosity, ordering, BLR, refinement, threads);
    // defaults as documented in config/solid.example.yaml. symmetric and reuseFactorization are
    // set by fe::StructuralSolver.
    linalg::DirectSolverOptions linearSolver;
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
