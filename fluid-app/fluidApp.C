// SPDX-License-Identifier: GPL-3.0-or-later
/*---------------------------------------------------------------------------*\
Application
    fluid-app

Description
    Steady incompressible SIMPLE/SIMPLEC solver with mesh motion, the fluid
    side of the FSI toolkit (DESIGN.md section 5). Kinematic pressure; flow
    model from constant/turbulenceProperties (laminar by default); mesh motion
    from constant/dynamicMeshDict (dynamicMotionSolverFvMesh +
    displacementLaplacian). Coupling settings in system/fsiDict.

    Modes (fsiDict 'mode', default coupled, or one of the command-line switches;
    resolved once, coupling/runMode.H):
      -rigid       no coupling: solve steady to convergence, log and write forces
      -prescribed  prescribed interface motion from fsiDict 'prescribed' (tests)
      -coupled     coupled with solid-app through fsi::comm

Usage
    fluid-app [-rigid | -prescribed | -coupled [-restart]] [-parallel] [-case DIR]
              [--launch port|mpmd] [--port-file FILE] [--comm-timeout SECONDS]
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "dynamicFvMesh.H"
#include "singlePhaseTransportModel.H"
#include "turbulentTransportModel.H"
#include "fluidSolidCoupling.H"
#include "runMode.H"
#include "simpleAcceleration.H"

#include <cmath>
#include <cstdlib>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

int main(int argc, char* argv[])
{
    #include "heapSettings.H"
    // Before argList: the run mode decides whether MPI starts here (coupled: fsi::comm and the
    // MPMD world redirect, so that Pstream sees only the fluid's ranks).
    const fsi::fluid::RunMode mode = fsi::fluid::resolveRunMode(argc, argv);
    fsi::fluid::initialiseComm(argc, argv, mode);

    #include "setOptions.H"
    #include "setRootCase.H"
    #include "createTime.H"
    #include "createDynamicFvMesh.H"
    #include "createFields.H"
    #include "initContinuityErrs.H"

    turbulence->validate();
    fluidSolidCoupling coupling(mesh, U, p, phi, turbulence());
    simpleAcceleration acceleration(simpleAcceleration::Settings::read(simpleDict), U, p, phi);
    Info<< acceleration.describe().c_str() << nl << endl;

    #include "steadySolve.H"

    const int rc = coupling.run(mode, steadySolve, args.found("restart"));

    runTime.printExecutionTime(Info);
    Info<< "End\n" << endl;
    if (rc != 0)
    {
        UPstream::exit(rc);
    }
    return 0;
}
