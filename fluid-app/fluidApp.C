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

    Modes (fsiDict 'mode', default coupled, or the command-line switches):
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

#include <cmath>

int main(int argc, char* argv[])
{
    // Before argList: strips the comm flags, starts MPI and the MPMD world
    // redirect (coupled mode) so that Pstream sees only the fluid's ranks.
    fsi::fluid::initialiseComm(argc, argv);

    argList::addNote
    (
        "Steady incompressible SIMPLE solver with mesh motion, coupled to solid-app."
    );
    argList::addBoolOption("rigid", "Uncoupled: solve steady to convergence and write forces");
    argList::addBoolOption("prescribed", "Prescribed interface motion from system/fsiDict (tests)");
    argList::addBoolOption("coupled", "Coupled with solid-app through fsi::comm (overrides fsiDict mode)");
    argList::addBoolOption
    (
        "restart",
        "Coupled: continue a run from controlDict's startTime (set by scripts/fsi-restart-fluid)"
        " together with solid-app --restart; appends to the postProcessing/fsi logs"
    );

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createDynamicFvMesh.H"
    #include "createFields.H"
    #include "initContinuityErrs.H"

    turbulence->validate();

    fluidSolidCoupling coupling(mesh, U, p, phi, turbulence());

    word mode = coupling.dict().getOrDefault<word>("mode", "coupled");
    if (args.found("rigid"))
    {
        mode = "rigid";
    }
    if (args.found("prescribed"))
    {
        mode = "prescribed";
    }
    if (args.found("coupled"))
    {
        mode = "coupled";
    }

    // One SIMPLE iteration per time increment (time = iteration counter).
    // Stops on the absolute residualControl of fvSolution::SIMPLE, or on the
    // relative drop of fsiDict, and (optionally) on force convergence.
    bool solveFlow = true;
    auto steadySolve = [&](const fluidSolidCoupling::SolveControls& ctrl)
    {
        fluidSolidCoupling::SolveResult result;
        if (!solveFlow)
        {
            result.converged = true;
            return result;
        }
        scalar firstU = -1, firstP = -1;
        vector previousForce(Zero);
        DynamicList<scalar> forceChanges;   // |F_k - F_k-1| of this solve
        label stable = 0;                   // consecutive iterations meeting the criteria
        for (label iter = 1; iter <= ctrl.maxIterations; ++iter)
        {
            ++runTime;
            scalar residualU = 0;
            scalar residualP = 0;
            p.storePrevIter();
            {
                #include "UEqn.H"
                #include "pEqn.H"
            }
            laminarTransport.correct();
            turbulence->correct();

            if (iter == 1)
            {
                firstU = residualU;
                firstP = residualP;
            }
            result.iterations = iter;
            result.residualU = residualU;
            result.residualP = residualP;
            if (!std::isfinite(residualU) || !std::isfinite(residualP))
            {
                break;   // diverged: the coupling class stops the run
            }

            const bool dropOk =
                ctrl.residualDrop > 0
             && residualU <= ctrl.residualDrop*firstU
             && residualP <= ctrl.residualDrop*firstP;
            const bool absoluteOk = residualU <= tolU && residualP <= tolP;
            const bool residualOk = !ctrl.residualRequired || dropOk || absoluteOk;
            bool forceOk = true;
            if (ctrl.forceTolerance > 0)
            {
                const vector F = coupling.interfaceForce();
                const scalar change = mag(F - previousForce);
                previousForce = F;
                if (iter > 1)
                {
                    forceChanges.append(change);
                }
                scalar error = change;
                if (ctrl.estimateError && iter > 1)
                {
                    // What is left of a linearly converging iteration: change rho/(1 - rho),
                    // rho over the last three ratios of changes (0.9 until four changes are
                    // known), at most 0.98.
                    const label m = forceChanges.size();
                    scalar rho = 0.9;
                    if (m >= 4 && forceChanges[m - 4] > VSMALL)
                    {
                        rho = Foam::pow(forceChanges[m - 1]/forceChanges[m - 4], 1.0/3.0);
                    }
                    rho = min(max(rho, scalar(0)), scalar(0.98));
                    error = change*rho/(1 - rho);
                }
                forceOk = iter > 1 && error <= ctrl.forceTolerance*mag(F);
            }
            stable = (residualOk && forceOk) ? stable + 1 : 0;
            if (stable >= ctrl.stableIterations && iter >= ctrl.minIterations)
            {
                result.converged = true;
                Info<< "SIMPLE converged in " << iter << " iterations" << nl << endl;
                break;
            }
        }
        return result;
    };

    int rc = 0;
    if (mode == "rigid")
    {
        rc = coupling.runRigid(steadySolve);
    }
    else if (mode == "prescribed")
    {
        const dictionary& pd = coupling.dict().subDict("prescribed");
        solveFlow = pd.getOrDefault<bool>("solveFlow", false);
        rc = coupling.runCoupled(steadySolve, fluidSolidCoupling::prescribedTransport(pd));
    }
    else if (mode == "coupled")
    {
        if (!fsi::fluid::commAvailable())
        {
            FatalErrorInFunction
                << "coupled mode needs fsi::comm; this fluid-app was built without comm/"
                << exit(FatalError);
        }
        rc = coupling.runCoupled
        (
            steadySolve,
            fsi::fluid::makeCommTransport(),
            args.found("restart")
        );
    }
    else
    {
        FatalIOErrorInFunction(coupling.dict())
            << "system/fsiDict: mode must be coupled, rigid or prescribed, got "
            << mode << exit(FatalIOError);
    }

    runTime.printExecutionTime(Info);
    Info<< "End\n" << endl;
    if (rc != 0)
    {
        UPstream::exit(rc);
    }
    return 0;
}
