// SPDX-License-Identifier: GPL-3.0-or-later
//
// Restart files of a coupled run, one folder per checkpointed level:
//   OUT/checkpoint/level_NNNN/solid_rank_R.bin  each solid rank's committed state (fe layer)
//   OUT/checkpoint/level_NNNN/driver.bin        the driver's state (rank 0)
//   OUT/checkpoint/latest                       "level N", "time T [s]", "folder level_NNNN"
// `latest` is replaced (atomically) only after every file of the level is in place, so a run
// killed at any moment leaves the previous complete checkpoint as `latest`. Older level folders
// beyond `keep` are removed. The fluid keeps its own fields (OpenFOAM time folders of accepted
// levels); they are only the fluid's starting guess, the restarted level is solved from the
// checkpointed interface displacement.
#pragma once

#include "acceleration/Accelerator.hpp"
#include "fe/StructuralSolver.hpp"

#include <mpi.h>

#include <limits>
#include <string>
#include <vector>

namespace fsi::driver
{

// `coupling.checkpoint` block.
struct CheckpointParameters
{
    int every = 1; // checkpoint every N accepted levels (0 = never); the last level always
    int keep = 2;  // complete checkpoints kept on disk (>= 1)
    // Throws std::runtime_error naming coupling.checkpoint.<key>.
    void validate() const;
};

// What the driver carries from one level to the next.
struct DriverState
{
    int level = 0;         // the accepted level
    double time = 0.0;     // [s]
    double lastStep = 0.0; // dt of that level [s] (schedule state, linear predictor)
    std::vector<double> interfaceDisplacement;         // u_n, wetted nodes [m]
    std::vector<double> previousInterfaceDisplacement; // u_{n-1} [m]
    // Nodal fluid forces F_n, F_{n-1} on the wetted nodes [N] (the structural predictors).
    // Optional in the archive (older checkpoints: empty).
    std::vector<double> interfaceForce, previousInterfaceForce;
    // The secant predictor's samples (SecantFluidModel::State). Optional in the archive.
    std::vector<int> secantMeta;
    std::vector<double> secantValues;
    acceleration::AcceleratorState accelerator;
    double relaxationScale = 1.0; // product of the relaxation cures applied so far
    // Measures of the accepted level that steer the next one: its first coupling residual
    // (the forcing term's estimate for the next level's first iterate) [m] and its path error
    // (the adaptive schedule); NaN when unknown. Optional in the archive (older checkpoints).
    double firstResidual = 0.0;
    double pathError = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> acceptedTimes; // every accepted level so far [s] (the PVD series)
    // Run totals so far.
    int couplingIterations = 0, fluidIterations = 0, factorizations = 0;
    double wallSeconds = 0.0, fluidSeconds = 0.0, solidSeconds = 0.0, mappingSeconds = 0.0;
};

// Collective: throws std::runtime_error on every rank, with the message of the lowest failing
// rank, when any rank's localError is not empty.
void throwIfAnyRankFailed(MPI_Comm comm, const std::string& localError);

class CheckpointStore
{
public:
    // folder: OUT/checkpoint. Collective constructor (no I/O).
    CheckpointStore(MPI_Comm comm, std::string folder, int keep);

    // Collective: writes this rank's solid state and (rank 0) the driver state for `driver.level`,
    // then points `latest` at it and prunes. Throws (on every rank) when a file cannot be written.
    void write(const DriverState& driver, const fe::CommittedState& solid) const;

    struct Loaded
    {
        DriverState driver;
        std::vector<fe::CommittedState> solid; // one per rank of the saving run
        std::string folder;                    // the level folder it came from
    };
    // Collective: the checkpoint `latest` points at (same result on every rank). Throws a
    // one-line error naming the file when there is none or it is damaged.
    Loaded loadLatest() const;

    const std::string& folder() const { return folder_; }

private:
    MPI_Comm comm_;
    int rank_ = 0, size_ = 1;
    std::string folder_;
    int keep_ = 2;
};

} // namespace fsi::driver
