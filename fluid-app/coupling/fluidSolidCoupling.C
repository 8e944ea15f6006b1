// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the fluid side of the FSI coupling (see fluidSolidCoupling.H): set-up, the
// solve controls and the run modes (the command loop). Addressing, motion, forces and logging
// are in fluidSolidCoupling{Addressing,Motion,Forces,IO}.C.
#include "fluidSolidCoupling.H"

#include "points0MotionSolver.H"
#include "clockTime.H"

#include <cmath>

// * * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

// Prints the CPU time of fluid-app since its Time was made (OpenFOAM's cpuTime, the
// ExecutionTime of the log: user + system, every thread), summed over its ranks (collective):
// the benchmarks (scripts/bench-fsi) split a run's CPU time by program with this line.
void reportFluidCpu(const Foam::Time& runTime)
{
    const Foam::scalar cpu =
        Foam::returnReduce(runTime.elapsedCpuTime(), Foam::sumOp<Foam::scalar>());
    Foam::Info<< "fsi: CPU of the fluid ranks " << cpu << " s (user + system, summed over "
        << Foam::Pstream::nProcs() << " rank(s))" << Foam::endl;
}

Foam::vector readVector(const Foam::dictionary& d, const Foam::word& key, const Foam::vector& def)
{
    return d.getOrDefault<Foam::vector>(key, def);
}

void toArray(const Foam::vector& v, double out[3])
{
    out[0] = v.x();
    out[1] = v.y();
    out[2] = v.z();
}

} // namespace

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fluidSolidCoupling::fluidSolidCoupling
(
    dynamicFvMesh& mesh,
    volVectorField& U,
    volScalarField& p,
    surfaceScalarField& phi,
    const incompressible::turbulenceModel& turbulence
)
:
    mesh_(mesh),
    U_(U),
    p_(p),
    phi_(phi),
    turbulence_(turbulence),
    dict_
    (
        IOobject
        (
            "fsiDict",
            mesh.time().system(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    patchName_(dict_.get<word>("interfacePatch")),
    patchi_(mesh.boundaryMesh().findPatchID(patchName_)),
    rho_(dict_.get<scalar>("rho")),
    maxNonOrth_(90),
    maxSkewness_(20),
    nGlobalPoints_(0),
    nGlobalFaces_(0),
    writeInterfaceData_(false),
    writeSolveIterations_(dict_.getOrDefault<bool>("writeSolveIterations", false)),
    warmStart_
    (
        mesh,
        flowWarmStart::Settings::read(dict_.subOrEmptyDict("coupled"), dict_.objectPath())
    )
{
    if (patchi_ < 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: interfacePatch '" << patchName_
            << "' is not a patch of the mesh; use one of "
            << mesh.boundaryMesh().names() << exit(FatalIOError);
    }
    if (rho_ <= 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: rho must be > 0 [kg/m^3], got " << rho_
            << exit(FatalIOError);
    }

    const wordList forcePatchNames
    (
        dict_.getOrDefault<wordList>("forcePatches", wordList(1, patchName_))
    );
    forcePatches_.setSize(forcePatchNames.size());
    forAll(forcePatchNames, i)
    {
        forcePatches_[i] = mesh.boundaryMesh().findPatchID(forcePatchNames[i]);
        if (forcePatches_[i] < 0)
        {
            FatalIOErrorInFunction(dict_)
                << "system/fsiDict: forcePatches entry '" << forcePatchNames[i]
                << "' is not a patch of the mesh" << exit(FatalIOError);
        }
    }

    const dictionary& quality = dict_.subOrEmptyDict("meshQuality");
    maxNonOrth_ = quality.getOrDefault<scalar>("maxNonOrthogonality", 85);
    maxSkewness_ = quality.getOrDefault<scalar>("maxSkewness", 10);
    writeInterfaceData_ = dict_.getOrDefault<bool>("writeInterfaceData", false);

    buildGlobalOrdering();

    const polyPatch& patch = mesh_.boundaryMesh()[patchi_];
    const labelList& meshPoints = patch.meshPoints();
    const pointIOField allPoints0(points0MotionSolver::points0IO(mesh_));
    if (allPoints0.size() != mesh_.nPoints())
    {
        FatalErrorInFunction
            << "the reference points " << allPoints0.objectPath() << " do not match the mesh ("
            << allPoints0.size() << " vs " << mesh_.nPoints() << " points)" << exit(FatalError);
    }
    points0_ = pointField(allPoints0, meshPoints);
    faceCentres0_.setSize(patch.size());
    faceAreas0_.setSize(patch.size());
    forAll(patch, facei)
    {
        faceCentres0_[facei] = patch[facei].centre(allPoints0);
        faceAreas0_[facei] = patch[facei].areaNormal(allPoints0);
    }
    displacement_ = vectorField(meshPoints.size(), Zero);
    slipNormals_ = slipWallNormals(allPoints0);

    Info<< "fsi: interface patch " << patchName_ << ": " << nGlobalPoints_
        << " points, " << nGlobalFaces_ << " faces; rho " << rho_
        << " kg/m^3; mesh limits: non-orthogonality " << maxNonOrth_
        << " deg, skewness " << maxSkewness_ << "; " << warmStart_.describe().c_str()
        << nl << endl;
    // both solve-control blocks are checked at start-up, whatever the mode (bad input stops
    // before anything runs)
    controls("rigid");
    controls("coupled");
}


Foam::fluidSolidCoupling::~fluidSolidCoupling() = default;


// * * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::fluidSolidCoupling::checkSolve(const fsi::fluid::Command& c)
{
    const label expected = 3*pointToGlobal_.size();
    const bool sizeOk = returnReduce(label(c.displacements.size()) == expected, andOp<bool>());
    if (!sizeOk)
    {
        failWith
        (
            "SOLVE step " + Foam::name(c.step) + " iteration " + Foam::name(c.iteration)
          + ": a rank received a number of interface displacements different from its "
          + "points (" + Foam::name(nGlobalPoints_) + " interface points in all)"
        );
    }
}


void Foam::fluidSolidCoupling::failWith(const string& message)
{
    if (transport_)
    {
        Perr<< "error: " << message.c_str() << endl;
        transport_->abortRun(message);   // comm: tells the peer and exits
    }
    FatalErrorInFunction << message << exit(FatalError);
}


void Foam::fluidSolidCoupling::checkDiverged(const SolveResult& r)
{
    if (!std::isfinite(r.residualU) || !std::isfinite(r.residualP))
    {
        failWith
        (
            "the steady flow solve diverged (non-finite residuals) at SIMPLE iteration "
          + Foam::name(r.iterations) + "; check the mesh, fvSchemes and relaxationFactors"
        );
    }
}


void Foam::fluidSolidCoupling::answerSolve
(
    const SteadySolver& solve,
    const SolveControls& own,
    const fsi::fluid::Command& c,
    const scalar wallSeconds
)
{
    Info<< "fsi: SOLVE step " << c.step << " iteration " << c.iteration << endl;
    moveInterface(c.displacements);
    if (c.accuracyGiven && !accuracyAnnounced_)
    {
        Info<< "fsi: the driver sets the accuracy of every solve (coupling.fluid_accuracy);"
            << " fsiDict coupled.residualDrop and coupled.forceTolerance are not used,"
            << " coupled.maxIterations " << own.maxIterations << " stays the cap and"
            << " coupled.stableIterations " << own.stableIterations << " the number of"
            << " consecutive iterations the estimate must hold, coupled.oscillationWindow "
            << own.oscillationWindow << " its window against turning points" << endl;
        accuracyAnnounced_ = true;
    }
    startFlow(c);
    solveStep_ = c.step;
    solveIteration_ = c.iteration;
    recordIterations_ = writeSolveIterations_;
    const SolveResult r = solve(c.accuracyGiven ? askedControls(own, c) : own);
    recordIterations_ = false;
    warmStart_.record(displacement_);
    if (c.accuracyGiven)
    {
        Info<< "fsi: asked force tolerance " << c.forceTolerance << ", residual drop "
            << c.residualDrop << ", at least " << c.minIterations << " iterations" << endl;
    }
    checkDiverged(r);

    fsi::fluid::ForceReport report;
    // A flow without a steady state that met the band rule answers with its mean.
    const vectorField f(r.inTheMean ? meanBlockForces() : faceForces(patchi_));
    report.faceForces.assign(3*f.size(), 0.0);
    forAll(f, facei)
    {
        for (direction k = 0; k < 3; ++k)
        {
            report.faceForces[3*facei + k] = f[facei][k];
        }
    }
    report.simpleIterations = r.iterations;
    report.residuals = {r.residualU, r.residualP};
    report.converged = r.converged;
    report.band = r.inTheMean ? r.band : 0;
    const vector total = gSum(f);
    Info<< "fsi: step " << c.step << " iteration " << c.iteration
        << ": " << r.iterations << " SIMPLE iterations"
        << (r.converged ? "" : " (cap reached)")
        << (r.inTheMean ? " (converged in the mean; the mean force is sent)" : "")
        << ", residuals U " << r.residualU << " p " << r.residualP
        << ", interface force " << total << " N" << endl;
    if (writeInterfaceData_)
    {
        writeInterfaceCsv
        (
            "interfaceForces_" + Foam::name(c.step) + "_" + Foam::name(c.iteration) + ".csv",
            gatherFaceForces(f), nGlobalFaces_, "i,fx,fy,fz"
        );
    }
    // every rank sends its own faces' forces to the solid (no gather here)
    const clockTime send;
    transport_->sendForces(c, report);
    const scalar exchangeSeconds =
        returnReduce(c.exchangeSeconds + send.elapsedTime(), maxOp<scalar>());
    logSolve(c, r, total, gMax(mag(displacement_)()), wallSeconds, exchangeSeconds);
}


void Foam::fluidSolidCoupling::startFlow(const fsi::fluid::Command& c)
{
    if (!warmStart_.settings().secant)
    {
        return;
    }
    const flowWarmStart::Prediction w = warmStart_.predict(displacement_);
    if (w.applied)
    {
        Info<< "fsi: step " << c.step << " iteration " << c.iteration
            << ": flow extrapolated from " << w.columns << " earlier interface change(s), "
            << 100*w.captured << " % of this change in their span, largest coefficient "
            << w.largestCoefficient << endl;
    }
    else
    {
        Info<< "fsi: step " << c.step << " iteration " << c.iteration
            << ": flow from the last solve (" << w.reason.c_str() << ")" << endl;
    }
}


void Foam::fluidSolidCoupling::acceptLevel(const fsi::fluid::Command& c)
{
    Info<< "fsi: ACCEPT step " << c.step << " time " << c.time << endl;
    reportForces("accepted");
    writeLevel(c.time);
    logAccepted(c);   // after the fields: a listed level is complete on disk (restart)
    if (solveIterationLog_.valid())
    {
        solveIterationLog_().flush();   // complete up to the accepted level
    }
}

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::fluidSolidCoupling::SolveControls Foam::fluidSolidCoupling::controls
(
    const word& subDictName
) const
{
    const dictionary& d = dict_.subOrEmptyDict(subDictName);
    SolveControls c;
    c.maxIterations = d.getOrDefault<label>("maxIterations", 1000);
    c.residualDrop = d.getOrDefault<scalar>("residualDrop", 0);
    c.forceTolerance = d.getOrDefault<scalar>("forceTolerance", 0);
    c.minIterations = d.getOrDefault<label>("minIterations", 1);
    c.residualRequired = d.getOrDefault<bool>("residualRequired", true);
    c.estimateError = d.getOrDefault<bool>("estimateForceError", false);
    c.stableIterations = d.getOrDefault<label>("stableIterations", 1);
    c.oscillationWindow = d.getOrDefault<label>("oscillationWindow", 0);
    c.bandTolerance = d.getOrDefault<scalar>("bandTolerance", 0);
    c.bandWindow = d.getOrDefault<label>("bandWindow", 100);
    c.bandMeanTolerance = d.getOrDefault<scalar>("bandMeanTolerance", 0);
    c.bandReferenceForce = d.getOrDefault<scalar>("bandReferenceForce", 0);
    if (c.bandReferenceForce < 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".bandReferenceForce "
            << c.bandReferenceForce << " is invalid: 0 (off: the band is relative to the mean"
            << " force) or the force scale in N (e.g. the level-0 lift)" << exit(FatalIOError);
    }
    if (c.bandMeanTolerance < 0 || c.bandMeanTolerance >= 1)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".bandMeanTolerance "
            << c.bandMeanTolerance << " is invalid: 0 (off: the asked force tolerance) or in"
            << " (0, 1) (relative change of the mean between two blocks)" << exit(FatalIOError);
    }
    if
    (
        c.bandTolerance < 0 || c.bandTolerance >= 1
     || (c.bandTolerance > 0 && (c.bandWindow < 10 || 2*c.bandWindow > c.maxIterations))
    )
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".bandTolerance " << c.bandTolerance
            << " / bandWindow " << c.bandWindow << " are invalid: bandTolerance 0 (off) or in"
            << " (0, 1) (relative half-width of the force band), bandWindow >= 10 SIMPLE"
            << " iterations and 2 bandWindow <= maxIterations " << c.maxIterations
            << exit(FatalIOError);
    }
    if (c.bandTolerance > 0 && c.forceTolerance <= 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".bandTolerance needs a forceTolerance"
            << " > 0 (it bounds the change of the mean between two blocks)"
            << exit(FatalIOError);
    }
    if (c.oscillationWindow != 0 && (c.oscillationWindow < 3 || c.oscillationWindow > 1000))
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".oscillationWindow "
            << c.oscillationWindow << " is invalid: 0 (off) or 3..1000 SIMPLE iterations"
            << " (about one period of the force's oscillation)" << exit(FatalIOError);
    }
    if
    (
        c.maxIterations < 1 || c.minIterations < 1 || c.minIterations > c.maxIterations
     || c.stableIterations < 1
    )
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".maxIterations, minIterations and"
            << " stableIterations must be >= 1 with minIterations <= maxIterations"
            << exit(FatalIOError);
    }
    if (!c.residualRequired && c.forceTolerance <= 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: " << subDictName << ".residualRequired false needs a"
            << " forceTolerance > 0 (otherwise nothing stops the solve before maxIterations)"
            << exit(FatalIOError);
    }
    return c;
}


Foam::fluidSolidCoupling::SolveControls Foam::fluidSolidCoupling::askedControls
(
    const SolveControls& own,
    const fsi::fluid::Command& solve
)
{
    SolveControls c;
    c.maxIterations = own.maxIterations;
    c.minIterations = max(1, solve.minIterations);
    c.forceTolerance = solve.forceTolerance;
    c.residualDrop = solve.residualDrop;
    c.residualRequired = solve.residualDrop > 0;
    c.estimateError = true;
    // The fluid's own guards against a pause of an oscillating force (fsiDict coupled)
    c.stableIterations = own.stableIterations;
    c.oscillationWindow = own.oscillationWindow;
    // and its rule for a flow without a steady state (the mean's change bounded by the asked
    // tolerance, or by the fluid's own bandMeanTolerance where that is larger)
    c.bandTolerance = own.bandTolerance;
    c.bandWindow = own.bandWindow;
    c.bandMeanTolerance = own.bandMeanTolerance;
    c.bandReferenceForce = own.bandReferenceForce;
    return c;
}


int Foam::fluidSolidCoupling::run
(
    const fsi::fluid::RunMode mode,
    const SteadySolver& solve,
    const bool restart
)
{
    switch (mode)
    {
        case fsi::fluid::RunMode::rigid:
            return runRigid(solve);
        case fsi::fluid::RunMode::prescribed:
            return runPrescribed(solve);
        case fsi::fluid::RunMode::coupled:
            break;
    }
    if (!fsi::fluid::commAvailable())
    {
        FatalErrorInFunction
            << "coupled mode needs fsi::comm; this fluid-app was built without comm/"
            << exit(FatalError);
    }
    return runCoupled(solve, fsi::fluid::makeCommTransport(), restart);
}


int Foam::fluidSolidCoupling::runRigid(const SteadySolver& solve)
{
    Info<< "fsi: rigid mode (no coupling): steady solve to convergence" << nl << endl;
    // time = SIMPLE iterations (deltaT 1): a run from a written time T > 0 goes on from T
    const Time& time = mesh_.time();
    rigidStartIteration_ = label(std::round(time.value()/time.deltaTValue()));
    rigidWriteInterval_ = dict_.subOrEmptyDict("rigid").getOrDefault<label>("writeInterval", 0);
    if (rigidWriteInterval_ < 0)
    {
        FatalIOErrorInFunction(dict_)
            << "system/fsiDict: rigid.writeInterval " << rigidWriteInterval_ << " is invalid:"
            << " 0 (off: fields written at the end only) or the SIMPLE iterations between"
            << " restart points (e.g. 200)" << exit(FatalIOError);
    }
    if (rigidStartIteration_ > 0)
    {
        Info<< "fsi: rigid solve goes on from the fields of iteration " << rigidStartIteration_
            << " (time " << time.timeName() << "); the stopping test starts anew" << endl;
    }
    openIterationLog();
    const SolveControls rigid = controls("rigid");
    if (rigid.bandTolerance > 0)
    {
        startFieldBlocks();   // a stop in the mean then reports the mean flow
    }
    SolveResult r = solve(rigid);
    closeIterationLog();
    checkDiverged(r);
    const label thisRun = r.iterations;
    r.iterations += rigidStartIteration_;   // forces.csv and the log: the whole solve's count
    Info<< "fsi: rigid solve: " << r.iterations << " SIMPLE iterations";
    if (rigidStartIteration_ > 0)
    {
        Info<< " (" << thisRun << " after the restart at iteration " << rigidStartIteration_
            << ")";
    }
    Info<< ", residuals U " << r.residualU << " p " << r.residualP
        << (r.converged ? " (converged)" : " (iteration cap reached)") << endl;
    reportFluidCpu(mesh_.time());
    if (r.inTheMean)
    {
        useMeanFields();
    }
    vector total(Zero), pressure(Zero);
    reportForces("rigid", &total, &pressure);
    checkAgainstForcesFunctionObject();
    writeRigidForces(r, total, pressure);
    writeInterfaceCsv
    (
        "interfaceForces_rigid.csv", gatherFaceForces(faceForces(patchi_)), nGlobalFaces_,
        "i,fx,fy,fz"
    );
    mesh_.time().printExecutionTime(Info);
    Time& runTime = const_cast<Time&>(mesh_.time());
    runTime.writeNow();
    return 0;
}


int Foam::fluidSolidCoupling::runCoupled
(
    const SteadySolver& solve,
    std::unique_ptr<fsi::fluid::CouplingTransport> transport,
    const bool restart
)
{
    using namespace fsi::fluid;
    transport_ = std::move(transport);
    const InterfaceGeometry geometry = gatherGeometry();
    LocalInterface local;
    local.pointRows.assign(pointToGlobal_.begin(), pointToGlobal_.end());
    local.faceRows.assign(faceToGlobal_.begin(), faceToGlobal_.end());
    local.pointCoordinates.reserve(3*points0_.size());
    for (const point& p : points0_)
    {
        local.pointCoordinates.insert(local.pointCoordinates.end(), {p.x(), p.y(), p.z()});
    }
    transport_->handshake(geometry, nGlobalPoints_, nGlobalFaces_, local);

    // The logs only once the solid is connected: a start that fails (no peer, wrong port file,
    // handshake mismatch) must not truncate accepted.csv, the restart point of an earlier run.
    openCouplingLogs(restart);
    if (restart)
    {
        Info<< "fsi: restarted from the fields of time " << mesh_.time().timeName() << nl << endl;
        if (warmStart_.settings().secant)
        {
            string why;
            const bool read = warmStart_.read(warmStartFile(), displacement_.size(), why);
            if (returnReduce(read, andOp<bool>()))
            {
                Info<< "fsi: warm start: the earlier solves' flows of that level read from "
                    << warmStartFile() << endl;
            }
            else
            {
                warmStart_.clear();   // on every rank, also where the file was read
                Info<< "fsi: warm start: starting without earlier solves (" << why.c_str()
                    << ")" << endl;
            }
        }
    }
    Info<< "fsi: coupled mode, transport: " << transport_->describe().c_str() << nl << endl;
    writeInterfaceGeometry(geometry);

    const SolveControls own = controls("coupled");
    const clockTime wall;
    while (true)
    {
        const Command c = transport_->receive();
        switch (c.kind)
        {
            case CommandKind::solve:
                checkSolve(c);
                answerSolve(solve, own, c, wall.elapsedTime());
                break;
            case CommandKind::accept:
                acceptLevel(c);
                break;
            case CommandKind::finish:
                Info<< "fsi: FINISH after " << wall.elapsedTime() << " s" << endl;
                reportFluidCpu(mesh_.time());
                return 0;
            case CommandKind::abort:
                Perr<< "error: the solid side aborted: " << c.reason.c_str() << endl;
                return 2;
        }
    }
}


int Foam::fluidSolidCoupling::runPrescribed(const SteadySolver& solve)
{
    const dictionary& pd = dict_.subDict("prescribed");
    const bool solveFlow = pd.getOrDefault<bool>("solveFlow", false);
    // solveFlow false: the mesh moves and the forces of the unchanged flow are returned
    const SteadySolver frozen = [](const SolveControls&)
    {
        SolveResult r;
        r.converged = true;
        return r;
    };
    return runCoupled(solveFlow ? solve : frozen, prescribedTransport(pd));
}


std::unique_ptr<fsi::fluid::CouplingTransport>
Foam::fluidSolidCoupling::prescribedTransport(const dictionary& dict)
{
    fsi::fluid::PrescribedMotion m;
    m.type = dict.get<word>("type");
    if (m.type != "rotation" && m.type != "bending" && m.type != "twist")
    {
        FatalIOErrorInFunction(dict)
            << "system/fsiDict: prescribed.type must be rotation, bending or twist, got "
            << m.type << exit(FatalIOError);
    }
    toArray(readVector(dict, "origin", Zero), m.origin);
    toArray(normalised(readVector(dict, "axis", vector(0, 0, 1))), m.axis);
    m.angleDeg = dict.getOrDefault<scalar>("angle", 0);
    toArray(normalised(readVector(dict, "beamAxis", vector(1, 0, 0))), m.beamAxis);
    toArray(normalised(readVector(dict, "direction", vector(0, 1, 0))), m.direction);
    m.start = dict.getOrDefault<scalar>("start", 0);
    m.length = dict.getOrDefault<scalar>("length", 1);
    m.amplitude = dict.getOrDefault<scalar>("amplitude", 0);
    m.steps = dict.getOrDefault<label>("steps", 1);
    if (m.type != "rotation" && !(m.length > 0))
    {
        FatalIOErrorInFunction(dict)
            << "system/fsiDict: prescribed.length must be > 0 [m] (the beam's normalising"
            << " length), got " << m.length << exit(FatalIOError);
    }
    if (m.steps < 1)
    {
        FatalIOErrorInFunction(dict)
            << "system/fsiDict: prescribed.steps must be >= 1, got " << m.steps
            << exit(FatalIOError);
    }
    return fsi::fluid::makePrescribedTransport(m);
}

// ************************************************************************* //
