// SPDX-License-Identifier: GPL-3.0-or-later
// MPI start-up and the MPMD split of MPI_COMM_WORLD.
//
// OpenFOAM v1912's libPstream uses MPI_COMM_WORLD as its world. Under
// `mpirun -np A fluid-app : -np B solid-app` that world holds both programs. The fluid
// executable therefore links the target fsi_comm_world_redirect, which defines the MPI_*
// functions libPstream imports; once initialiseMpmdWorld() has run, any of them given
// MPI_COMM_WORLD acts on the fluid's own ranks (a private duplicate of the split
// communicator) and then calls the PMPI_* version. See comm/README.md.
#pragma once

#include "fsi/comm/LaunchOptions.hpp"

#include <mpi.h>

#include <vector>

namespace fsi
{
namespace comm
{

// Initialises MPI (MPI_THREAD_FUNNELED) unless it already runs. Idempotent.
void initialiseMpi(int& argc, char**& argv);
// Finalises MPI if initialised and not yet finalised. Idempotent.
void finaliseMpi();

// The layout of an MPMD launch, computed once per process.
struct MpmdLayout
{
    int appNumber = 0; // MPI_APPNUM of this process (0 = first program on the line)
    int appCount = 0;  // number of programs in the launch
    int worldRank = 0; // rank in the real MPI_COMM_WORLD
    int worldSize = 0;
    std::vector<int> appLeaders;          // real world rank of each program's first process
    MPI_Comm programComm = MPI_COMM_NULL; // this program's ranks; owned by the library
};

// What the launcher tells this process about the launch, without any communication (MPI must
// be initialised): MPI_APPNUM, and Open MPI's OMPI_NUM_APP_CTX / OMPI_APP_CTX_NUM_PROCS.
struct LaunchShape
{
    int programs = 1;       // programs started by this mpirun (1 if the launcher does not say)
    int appNumber = 0;      // MPI_APPNUM of this process
    int worldRank = 0;      // rank in the real MPI_COMM_WORLD
    int firstWorldRank = 0; // real world rank of this program's first process
};
LaunchShape launchShape();
// True if this process shares its mpirun (its MPI_COMM_WORLD) with another program: an MPMD
// launch. Then an error before the coupling exists must end the whole job (MPI_Abort), since
// the peer waits in the MPMD split or in MPI_Finalize, both collective over the whole job.
bool multiProgramLaunch();

// Collective over the REAL MPI_COMM_WORLD on the first call: every process of the launch must
// call it exactly once first (Channel::open does so in MPMD mode; the fluid through
// initialiseMpmdWorld). Bounded by a watchdog (timeoutSeconds). Throws CommError if the
// launch does not have exactly two programs.
const MpmdLayout& mpmdLayout(double timeoutSeconds);

// Fluid executable entry, defined in fsi_comm_world_redirect. Call first in main, BEFORE
// OpenFOAM's argList: removes --launch/--port-file/--comm-timeout from argc/argv, initialises
// MPI, and in MPMD mode splits MPI_COMM_WORLD and switches the redirect on. Throws
// std::runtime_error if the options are bad or the redirect symbols are not exported from
// the executable (link fsi_comm_world_redirect as README.md says).
LaunchOptions initialiseMpmdWorld(int& argc, char**& argv);

// Defined in fsi_comm_world_redirect: the communicator MPI_COMM_WORLD currently maps to
// (MPI_COMM_NULL when the redirect is off).
MPI_Comm worldRedirectTarget();

} // namespace comm
} // namespace fsi
