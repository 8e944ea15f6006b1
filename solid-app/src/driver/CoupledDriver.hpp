// SPDX-License-Identifier: GPL-3.0-or-later
//
// The quasi-steady coupling loop (the paper's figure 4), run by solid-app. Per time level:
//   u_0 = predictor (from past levels);  accelerator.beginLevel()
//   iterate i = 1, 2, ...:
//     map u_{i-1} (solid wetted nodes) -> fluid points (consistent); the fluid solves the steady
//     flow to the accuracy the forcing term asks for (FluidAccuracy.hpp)
//     map face forces -> solid wetted nodes (conservative), solid solves equilibrium -> u_hat_i
//     r_i = u_hat_i - u_{i-1}; converged when |r_i|/sqrt(n) < eps (and/or relative criterion)
//       and the last fluid solve met the final accuracy
//     u_i = accelerator.update(u_{i-1}, u_hat_i)
//   on convergence: commit the material history, the fluid writes its fields, outputs are written.
// A level that diverges, hits max_iterations or whose structural Newton solve fails is redone
// with a cure (RecoveryPolicy.hpp), announced as "[cure]"; when the cures are used up the run
// stops with the diagnosis (on_max_iterations: continue accepts a capped level instead, loudly).
// Logs: CouplingLog.hpp; post-processing columns: LevelProbe.hpp. Every `checkpoint.every`
// accepted levels the state is written to OUT/checkpoint (Checkpoint.hpp) and setRestart(true)
// continues from there. Collective on the solid communicator; only rank 0 talks to the fluid.
#pragma once

#include "acceleration/Accelerator.hpp"
#include "driver/CouplingParameters.hpp"
#include "driver/FluidPeer.hpp"
#include "driver/LevelProbe.hpp"
#include "fe/StructuralSolver.hpp"
#include "mapping/Mapping.hpp"

#include <mpi.h>

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fsi::driver
{

struct LevelRecord
{
    int level = 0;
    double time = 0.0; // [s]
    double dt = 0.0;   // [s]
    int couplingIterations = 0;
    int fluidIterations = 0;  // summed over the level's coupling iterations
    int newtonIterations = 0; // summed
    double residual = 0.0;    // |r|/sqrt(n) at acceptance [m]
    bool converged = false;
    Eigen::Vector3d force = Eigen::Vector3d::Zero(); // total fluid force on the structure [N]
    std::vector<double> probes;  // the LevelProbes' values, in their column order
    double relativeChange = 0.0; // |u_n - u_{n-1}| / |u_n| of the interface displacement
    // |u_n - u_lin| / |u_n|, u_lin the linear extrapolation of the two levels before (the
    // error of the quasi-steady path, schedule/Adaptive.hpp); NaN when fewer levels exist
    double pathError = std::numeric_limits<double>::quiet_NaN();
    double firstResidual = 0.0; // |r|/sqrt(n) of the level's first coupling iteration [m]
    double wallSeconds = 0.0;   // since the start of the run (restarts included)
    int retries = 0;            // automatic cures applied to this level
};

struct RunSummary
{
    int levels = 0;
    int couplingIterations = 0;
    int fluidIterations = 0;
    int factorizations = 0;
    double wallSeconds = 0.0;
    double fluidSeconds = 0.0, solidSeconds = 0.0, mappingSeconds = 0.0;
    std::vector<LevelRecord> history;
};

class CoupledDriver
{
public:
    // solid: the structural solver (not owned, outlives the driver). fluid: the fluid peer,
    // non-null on every rank of `comm` (not owned; called collectively). outputFolder: where
    // coupling.csv, history.csv and interface/ are written (rank 0; created if missing).
    // relaxationTimes: the material's Prony tau_i (empty: elastic) for the adaptive time
    // schedule. probes: post-processing quantities written per accepted level (LevelProbe.hpp).
    CoupledDriver(MPI_Comm comm, fe::StructuralSolver& solid, FluidPeer* fluid,
                  CouplingParameters params, std::string outputFolder,
                  std::vector<double> relaxationTimes, LevelProbes probes = {});
    ~CoupledDriver();

    // Called on every rank after each accepted level (e.g. to write VTU).
    void onLevelAccepted(std::function<void(const LevelRecord&)> callback);
    // Prints one progress line per level and per coupling iteration on rank 0 (default on).
    void setVerbose(bool verbose) { verbose_ = verbose; }
    // Continue from OUT/checkpoint/latest instead of t = 0: restores the solid, the driver and
    // the accelerator, keeps the rows of coupling.csv/history.csv up to that level.
    void setRestart(bool restart) { restart_ = restart; }
    // Times of every accepted level so far, restarts included (filled by run()).
    const std::vector<double>& acceptedTimes() const;

    // Runs all levels. Throws std::runtime_error (one line) when a level fails; before throwing
    // the fluid is told to abort with the same reason.
    RunSummary run();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    bool verbose_ = true;
    bool restart_ = false;
};

} // namespace fsi::driver
