// SPDX-License-Identifier: GPL-3.0-or-later
//
// The driver's parameters: the `coupling:` block of the solid-app config (every key is
// documented in config/coupled.example.yaml). Each strategy keeps its own coefficients block:
//   acceleration: { type: aitken, aitken: { initial_relaxation: 0.5 } }
//   mapping:      { type: rbf-wendland-c2, rbf-wendland-c2: { support_radius: 0.004 } }
//   force_mapping: { type: nearest-projection }   (optional: forces mapped by another strategy)
#pragma once

#include "acceleration/Accelerator.hpp"
#include "acceleration/Convergence.hpp"
#include "driver/Checkpoint.hpp"
#include "driver/FluidAccuracy.hpp"
#include "driver/SecantFluidModel.hpp"
#include "mapping/Mapping.hpp"
#include "schedule/Planned.hpp"
#include "schedule/Registry.hpp"

#include <array>
#include <optional>
#include <string>

namespace fsi::config
{
class Block;
}

namespace fsi::driver
{

// Angle of a section chord (e.g. the tip AOA): the chord from trailing to leading edge in the
// deformed state, measured in the plane (chord direction, lift direction), degrees, positive
// when the leading edge moves towards the lift direction.
struct SectionAngleParameters
{
    std::string name = "section_angle";
    std::array<double, 3> leadingEdge{};   // reference position [m] (nearest wetted node used)
    std::array<double, 3> trailingEdge{};  // [m]
    std::array<double, 3> liftDirection{}; // unit vector (normalised on parse)
};

struct LaunchParameters
{
    std::string mode = "mpmd";         // mpmd | port (the --launch flag overrides)
    std::string portFile = "fsi.port"; // port mode: relative to the run folder
    double timeout = 600.0;            // [s] longest wait for the fluid's answer
};

// `coupling.recovery`: what the driver does, automatically and loudly, when a level fails.
//   a coupling level diverges (residual growth, NaN) or hits max_iterations
//       -> the level is redone with a fresh accelerator and the initial relaxation x
//       relaxation_factor
//   the structural Newton fails after its own load sub-stepping (level > 0)
//       -> the level is redone with the time step x step_factor (the schedule then grows back)
// Each level gets at most max_retries such retries; then the run stops with the diagnosis.
struct RecoveryParameters
{
    int maxRetries = 3;            // per level (0 = no automatic cures)
    double relaxationFactor = 0.5; // in (0, 1)
    double stepFactor = 0.25;      // in (0, 1)
};

struct CouplingParameters
{
    LaunchParameters launch;
    int maxIterations = 30;               // per level
    bool continueOnMaxIterations = false; // false: a level that hits the cap stops the run
    double divergenceFactor = 1e3;        // stop when |r| grows past this x the level's first |r|
    std::string predictor = "linear";     // first iterate of a level: constant | linear | ...
    SecantParameters secant;              // the secant model of the fluid (predictor secant)
    std::optional<FluidAccuracyParameters> fluidAccuracy; // absent: the fluid's own controls
    acceleration::ConvergenceParameters convergence;
    acceleration::AcceleratorParameters acceleration;
    mapping::MappingParameters mapping; // displacements (and forces if no force_mapping)
    std::optional<mapping::MappingParameters> forceMapping; // forces' own strategy (optional)
    schedule::ScheduleParameters time = schedule::SteadyParameters{}; // no block: one level
    std::optional<SectionAngleParameters> sectionAngle;
    CheckpointParameters checkpoint;
    RecoveryParameters recovery;

    // Parses and validates the `coupling` block. Throws one-line errors (file, key, fix).
    static CouplingParameters parse(const config::Block& coupling);
    // Resolved values, YAML, for the start-up echo.
    std::string echo() const;
};

} // namespace fsi::driver
