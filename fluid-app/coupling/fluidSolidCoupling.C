// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the fluid side of the FSI coupling (see fluidSolidCoupling.H).
#include "fluidSolidCoupling.H"

#include "fvc.H"
#include "OFstream.H"
#include "labelIOList.H"
#include "pointFields.H"
#include "valuePointPatchFields.H"
#include "fixedValuePointPatchFields.H"
#include "polyMeshTools.H"
#include "ListOps.H"
#include "forces.H"
#include "points0MotionSolver.H"
#include "unitConversion.H"
#include "clockTime.H"

#include <algorithm>
#include <cmath>
#include <sstream>

// * * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

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
    writeInterfaceData_(false)
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

    Info<< "fsi: interface patch " << patchName_ << ": " << nGlobalPoints_
        << " points, " << nGlobalFaces_ << " faces; rho " << rho_
        << " kg/m^3; mesh limits: non-orthogonality " << maxNonOrth_
        << " deg, skewness " << maxSkewness_ << nl << endl;
}


Foam::fluidSolidCoupling::~fluidSolidCoupling() = default;


// * * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::fluidSolidCoupling::buildGlobalOrdering()
{
    const polyPatch& pp = mesh_.boundaryMesh()[patchi_];
    const labelList& meshPoints = pp.meshPoints();

    // Global (undecomposed) labels of the local patch points and faces
    labelList pointIds(meshPoints);
    labelList faceIds(identity(pp.size(), pp.start()));
    if (Pstream::parRun())
    {
        const labelIOList pointAddr
        (
            IOobject
            (
                "pointProcAddressing",
                mesh_.facesInstance(),
                polyMesh::meshSubDir,
                mesh_,
                IOobject::MUST_READ,
                IOobject::NO_WRITE,
                false
            )
        );
        const labelIOList faceAddr
        (
            IOobject
            (
                "faceProcAddressing",
                mesh_.facesInstance(),
                polyMesh::meshSubDir,
                mesh_,
                IOobject::MUST_READ,
                IOobject::NO_WRITE,
                false
            )
        );
        forAll(meshPoints, i)
        {
            pointIds[i] = pointAddr[meshPoints[i]];
        }
        forAll(faceIds, i)
        {
            faceIds[i] = mag(faceAddr[pp.start() + i]) - 1;
        }
    }

    // Points: sorted unique global labels, built on the master
    List<labelList> procPointIds(Pstream::nProcs());
    procPointIds[Pstream::myProcNo()] = pointIds;
    Pstream::gatherList(procPointIds);
    labelList sortedIds;
    if (Pstream::master())
    {
        DynamicList<label> all;
        for (const labelList& ids : procPointIds)
        {
            all.append(ids);
        }
        std::sort(all.begin(), all.end());
        auto last = std::unique(all.begin(), all.end());
        sortedIds = labelList(SubList<label>(all, label(last - all.begin())));
    }
    Pstream::scatter(sortedIds);
    nGlobalPoints_ = sortedIds.size();
    pointToGlobal_.setSize(pointIds.size());
    forAll(pointIds, i)
    {
        pointToGlobal_[i] = findSortedIndex(sortedIds, pointIds[i]);
    }

    // Faces: the undecomposed patch is contiguous; its start is the smallest label
    label start = faceIds.size() ? min(faceIds) : labelMax;
    reduce(start, minOp<label>());
    nGlobalFaces_ = returnReduce(faceIds.size(), sumOp<label>());
    faceToGlobal_ = faceIds - start;
    if (faceToGlobal_.size() && max(faceToGlobal_) >= nGlobalFaces_)
    {
        FatalErrorInFunction
            << "interface patch " << patchName_ << " is not contiguous in the"
            << " undecomposed mesh (faceProcAddressing); re-run decomposePar"
            << exit(FatalError);
    }
}


fsi::fluid::InterfaceGeometry Foam::fluidSolidCoupling::gatherGeometry() const
{
    const label nProcs = Pstream::nProcs(), me = Pstream::myProcNo();

    List<labelList> pIds(nProcs), fIds(nProcs);
    List<pointField> pts(nProcs), ctrs(nProcs), areas(nProcs);
    pIds[me] = pointToGlobal_;
    fIds[me] = faceToGlobal_;
    pts[me] = points0_;
    ctrs[me] = faceCentres0_;
    areas[me] = faceAreas0_;
    Pstream::gatherList(pIds);
    Pstream::gatherList(fIds);
    Pstream::gatherList(pts);
    Pstream::gatherList(ctrs);
    Pstream::gatherList(areas);

    fsi::fluid::InterfaceGeometry g;
    if (Pstream::master())
    {
        g.pointCoordinates.assign(3*nGlobalPoints_, 0.0);
        g.faceCentres.assign(3*nGlobalFaces_, 0.0);
        g.faceAreaVectors.assign(3*nGlobalFaces_, 0.0);
        for (label proci = 0; proci < nProcs; ++proci)
        {
            forAll(pIds[proci], i)
            {
                for (direction c = 0; c < 3; ++c)
                {
                    g.pointCoordinates[3*pIds[proci][i] + c] = pts[proci][i][c];
                }
            }
            forAll(fIds[proci], i)
            {
                for (direction c = 0; c < 3; ++c)
                {
                    g.faceCentres[3*fIds[proci][i] + c] = ctrs[proci][i][c];
                    g.faceAreaVectors[3*fIds[proci][i] + c] = areas[proci][i][c];
                }
            }
        }
    }
    return g;
}


std::vector<double> Foam::fluidSolidCoupling::gatherFaceForces
(
    const vectorField& localForces
) const
{
    const label nProcs = Pstream::nProcs(), me = Pstream::myProcNo();
    List<labelList> fIds(nProcs);
    List<vectorField> f(nProcs);
    fIds[me] = faceToGlobal_;
    f[me] = localForces;
    Pstream::gatherList(fIds);
    Pstream::gatherList(f);

    std::vector<double> out;
    if (Pstream::master())
    {
        out.assign(3*nGlobalFaces_, 0.0);
        for (label proci = 0; proci < nProcs; ++proci)
        {
            forAll(fIds[proci], i)
            {
                for (direction c = 0; c < 3; ++c)
                {
                    out[3*fIds[proci][i] + c] = f[proci][i][c];
                }
            }
        }
    }
    return out;
}


fsi::fluid::Command Foam::fluidSolidCoupling::broadcastCommand
(
    const fsi::fluid::Command& masterCommand
) const
{
    fsi::fluid::Command c = masterCommand;
    if (!Pstream::parRun())
    {
        return c;
    }
    label kind = label(c.kind), step = c.step, iteration = c.iteration;
    label accuracyGiven = c.accuracyGiven, minIterations = c.minIterations;
    scalar time = c.time, forceTolerance = c.forceTolerance, residualDrop = c.residualDrop;
    scalarList disp(c.displacements.size());
    forAll(disp, i)
    {
        disp[i] = c.displacements[i];
    }
    string reason(c.reason);
    Pstream::scatter(kind);
    Pstream::scatter(step);
    Pstream::scatter(iteration);
    Pstream::scatter(time);
    Pstream::scatter(disp);
    Pstream::scatter(reason);
    Pstream::scatter(accuracyGiven);
    Pstream::scatter(minIterations);
    Pstream::scatter(forceTolerance);
    Pstream::scatter(residualDrop);
    c.accuracyGiven = accuracyGiven;
    c.minIterations = minIterations;
    c.forceTolerance = forceTolerance;
    c.residualDrop = residualDrop;
    c.kind = fsi::fluid::CommandKind(kind);
    c.step = step;
    c.iteration = iteration;
    c.time = time;
    c.displacements.assign(disp.begin(), disp.end());
    c.reason = reason;
    return c;
}


bool Foam::fluidSolidCoupling::meshQualityOk() const
{
    const scalar minVol = gMin(mesh_.V().field());
    const scalarField ortho
    (
        polyMeshTools::faceOrthogonality(mesh_, mesh_.faceAreas(), mesh_.cellCentres())
    );
    const scalarField skew
    (
        polyMeshTools::faceSkewness
        (
            mesh_, mesh_.points(), mesh_.faceCentres(), mesh_.faceAreas(), mesh_.cellCentres()
        )
    );
    const scalar minOrtho = gMin(ortho);
    const scalar maxNonOrth = radToDeg(Foam::acos(min(scalar(1), max(scalar(-1), minOrtho))));
    const scalar maxSkew = gMax(skew);
    // Negative pyramid volumes = inverted or tangled cells
    const bool badPyramids =
        static_cast<const primitiveMesh&>(mesh_).checkFacePyramids(false, -SMALL);

    const bool ok =
        minVol > 0 && !badPyramids && maxNonOrth < maxNonOrth_ && maxSkew < maxSkewness_;
    Info<< "fsi: mesh after motion: min volume " << minVol
        << " m^3, max non-orthogonality " << maxNonOrth
        << " deg, max skewness " << maxSkew
        << (badPyramids ? ", NEGATIVE face pyramids (inverted cells)" : "")
        << (ok ? "  [ok]" : "  [FAILED]") << endl;
    return ok;
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


void Foam::fluidSolidCoupling::writeInterfaceCsv
(
    const fileName& name,
    const std::vector<double>& values,
    const label n,
    const std::string& header
) const
{
    if (!Pstream::master() || !writeInterfaceData_)
    {
        return;
    }
    OFstream os(mesh_.time().globalPath()/"postProcessing"/"fsi"/name);
    os.precision(17);
    os  << header.c_str() << nl;
    const label width = n ? label(values.size())/n : 0;
    for (label i = 0; i < n; ++i)
    {
        os  << i;
        for (label c = 0; c < width; ++c)
        {
            os  << ',' << values[width*i + c];
        }
        os  << nl;
    }
}


void Foam::fluidSolidCoupling::moveInterface
(
    const std::vector<double>& globalDisplacement
)
{
    if (label(globalDisplacement.size()) != 3*nGlobalPoints_)
    {
        failWith
        (
            "SOLVE carried " + Foam::name(label(globalDisplacement.size()/3))
          + " interface displacements, the fluid interface has "
          + Foam::name(nGlobalPoints_) + " points"
        );
    }
    forAll(displacement_, i)
    {
        const label g = pointToGlobal_[i];
        displacement_[i] = vector
        (
            globalDisplacement[3*g],
            globalDisplacement[3*g + 1],
            globalDisplacement[3*g + 2]
        );
    }

    pointVectorField* pdPtr =
        mesh_.lookupObjectRefPtr<pointVectorField>("pointDisplacement");
    if (!pdPtr)
    {
        failWith
        (
            "no pointDisplacement field: constant/dynamicMeshDict must select "
            "dynamicMotionSolverFvMesh with the displacementLaplacian solver"
        );
    }
    pointPatchVectorField& ppf = pdPtr->boundaryFieldRef()[patchi_];
    if (!isA<fixedValuePointPatchVectorField>(ppf))
    {
        failWith
        (
            "0/pointDisplacement: patch " + patchName_ + " must be fixedValue, is "
          + ppf.type()
        );
    }
    refCast<valuePointPatchVectorField>(ppf) == displacement_;

    const clockTime clock;
    mesh_.update();

    // The interface points must sit exactly on the prescribed positions
    const labelList& meshPoints = mesh_.boundaryMesh()[patchi_].meshPoints();
    scalar maxError = 0;
    forAll(meshPoints, i)
    {
        maxError =
            max(maxError, mag(mesh_.points()[meshPoints[i]] - (points0_[i] + displacement_[i])));
    }
    reduce(maxError, maxOp<scalar>());
    if (maxError > 1e-9*mesh_.bounds().mag())
    {
        WarningInFunction
            << "interface points are off the received positions by " << maxError
            << " m (2-D case with a displacement normal to the empty planes?)" << endl;
    }
    Info<< "fsi: mesh moved in " << clock.elapsedTime() << " s; max |x - (x0 + d)| on "
        << patchName_ << " = " << maxError << " m, max |d| = "
        << gMax(mag(displacement_)()) << " m" << endl;

    if (!meshQualityOk())
    {
        failWith
        (
            "mesh quality check failed after the interface motion (limits in "
            "system/fsiDict meshQuality); the last accepted level stays written"
        );
    }

    // Steady: fluxes from U on the moved mesh, no mesh-flux terms
    phi_ = fvc::flux(U_);
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


void Foam::fluidSolidCoupling::writeLevel(const scalar time)
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const scalar iterTime = runTime.value();
    const label iterIndex = runTime.timeIndex();
    runTime.setTime(time, iterIndex);
    Info<< "fsi: writing fields to time " << runTime.timeName() << nl << endl;
    runTime.writeNow();
    runTime.setTime(iterTime, iterIndex);
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
    return c;
}


Foam::tmp<Foam::vectorField> Foam::fluidSolidCoupling::faceForces
(
    const label patchi,
    vectorField* pressurePart
) const
{
    const vectorField& Sf = mesh_.Sf().boundaryField()[patchi];
    const scalarField& pb = p_.boundaryField()[patchi];
    const tmp<volSymmTensorField> tdevReff = turbulence_.devReff();
    const symmTensorField& devReffb = tdevReff().boundaryField()[patchi];

    const vectorField fp(rho_*Sf*pb);
    if (pressurePart)
    {
        *pressurePart = fp;
    }
    return tmp<vectorField>::New(fp + rho_*(Sf & devReffb));
}


Foam::vector Foam::fluidSolidCoupling::interfaceForce() const
{
    return gSum(faceForces(patchi_)());
}


void Foam::fluidSolidCoupling::reportForces
(
    const word& label,
    vector* totalOut,
    vector* pressureOut
) const
{
    vector total(Zero), pressure(Zero);
    for (const Foam::label patchi : forcePatches_)
    {
        vectorField fp;
        const tmp<vectorField> f = faceForces(patchi, &fp);
        total += gSum(f());
        pressure += gSum(fp);
    }
    Info<< "fsi: " << label << " force on " << dict_.getOrDefault<wordList>("forcePatches", wordList(1, patchName_))
        << ": total " << total << " N, pressure " << pressure
        << " N, viscous " << (total - pressure) << " N" << endl;
    if (totalOut)
    {
        *totalOut = total;
    }
    if (pressureOut)
    {
        *pressureOut = pressure;
    }
}


Foam::scalar Foam::fluidSolidCoupling::checkAgainstForcesFunctionObject() const
{
    wordList names(forcePatches_.size());
    forAll(forcePatches_, i)
    {
        names[i] = mesh_.boundaryMesh()[forcePatches_[i]].name();
    }
    dictionary foDict;
    foDict.add("type", "forces");
    foDict.add("patches", names);
    foDict.add("p", p_.name());
    foDict.add("U", U_.name());
    foDict.add("rho", "rhoInf");
    foDict.add("rhoInf", rho_);
    foDict.add("CofR", vector::zero);
    foDict.add("log", false);
    functionObjects::forces fo("fsiForceCheck", mesh_, foDict);
    fo.calcForcesMoment();
    const vector reference = fo.forceEff();

    vector ours(Zero);
    for (const label patchi : forcePatches_)
    {
        ours += gSum(faceForces(patchi)());
    }
    const scalar relDiff = mag(ours - reference)/max(mag(reference), VSMALL);
    Info<< "fsi: force check: sum of per-face forces " << ours
        << " N, functionObjects::forces " << reference
        << " N, relative difference " << relDiff << endl;
    return relDiff;
}


int Foam::fluidSolidCoupling::runRigid(const SteadySolver& solve)
{
    Info<< "fsi: rigid mode (no coupling): steady solve to convergence" << nl << endl;
    const SolveResult r = solve(controls("rigid"));
    checkDiverged(r);
    Info<< "fsi: rigid solve: " << r.iterations << " SIMPLE iterations, residuals U "
        << r.residualU << " p " << r.residualP
        << (r.converged ? " (converged)" : " (iteration cap reached)") << endl;
    vector total(Zero), pressure(Zero);
    reportForces("rigid", &total, &pressure);
    checkAgainstForcesFunctionObject();
    if (Pstream::master())
    {
        mkDir(mesh_.time().globalPath()/"postProcessing"/"fsi");
        OFstream os(mesh_.time().globalPath()/"postProcessing"/"fsi"/"forces.csv");
        os.precision(12);
        const vector viscous(total - pressure);
        os  << "Fx,Fy,Fz,pressureFx,pressureFy,pressureFz,viscousFx,viscousFy,viscousFz,"
            << "simpleIterations,converged,residualU,residualP,clock_s" << nl
            << total.x() << ',' << total.y() << ',' << total.z() << ','
            << pressure.x() << ',' << pressure.y() << ',' << pressure.z() << ','
            << viscous.x() << ',' << viscous.y() << ',' << viscous.z() << ','
            << r.iterations << ',' << int(r.converged) << ',' << r.residualU << ','
            << r.residualP << ',' << mesh_.time().elapsedClockTime() << nl;
    }
    {
        const std::vector<double> f = gatherFaceForces(faceForces(patchi_));
        if (Pstream::master() && writeInterfaceData_)
        {
            mkDir(mesh_.time().globalPath()/"postProcessing"/"fsi");
        }
        writeInterfaceCsv("interfaceForces_rigid.csv", f, nGlobalFaces_, "i,fx,fy,fz");
    }
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
    transport_->handshake(geometry, nGlobalPoints_, nGlobalFaces_);

    // The logs only once the solid is connected: a start that fails (no peer, wrong port file,
    // handshake mismatch) must not truncate accepted.csv, the restart point of an earlier run.
    const fileName logDir = mesh_.time().globalPath()/"postProcessing"/"fsi";
    if (Pstream::master())
    {
        mkDir(logDir);
        const bool append = restart && isFile(logDir/"coupling.csv");
        logFile_.reset
        (
            new OFstream
            (
                logDir/"coupling.csv",
                IOstream::ASCII,
                IOstream::currentVersion,
                IOstream::UNCOMPRESSED,
                append
            )
        );
        if (!append)
        {
            logFile_()
                << "step,iteration,simpleIterations,converged,residualU,residualP,"
                << "Fx,Fy,Fz,maxDisplacement,wall_s" << endl;
        }
        if (!restart || !isFile(logDir/"accepted.csv"))
        {
            OFstream(logDir/"accepted.csv")() << "step,time,timeName" << endl;
        }
    }
    if (restart)
    {
        Info<< "fsi: restarted from the fields of time " << mesh_.time().timeName() << nl << endl;
    }

    Info<< "fsi: coupled mode, transport: " << transport_->describe().c_str() << nl << endl;
    {
        std::vector<double> faceData(6*nGlobalFaces_);
        for (label i = 0; i < nGlobalFaces_ && Pstream::master(); ++i)
        {
            for (label c = 0; c < 3; ++c)
            {
                faceData[6*i + c] = geometry.faceCentres[3*i + c];
                faceData[6*i + 3 + c] = geometry.faceAreaVectors[3*i + c];
            }
        }
        writeInterfaceCsv("interfacePoints.csv", geometry.pointCoordinates, nGlobalPoints_, "i,x,y,z");
        writeInterfaceCsv("interfaceFaces.csv", faceData, nGlobalFaces_, "i,cx,cy,cz,Sx,Sy,Sz");
    }

    const SolveControls ctrl = controls("coupled");
    bool announced = false; // the first driver-controlled SOLVE says what it overrides
    const clockTime wall;
    while (true)
    {
        Command c = broadcastCommand(transport_->receive());

        switch (c.kind)
        {
            case CommandKind::solve:
            {
                Info<< "fsi: SOLVE step " << c.step << " iteration " << c.iteration << endl;
                moveInterface(c.displacements);
                if (c.accuracyGiven && !announced)
                {
                    Info<< "fsi: the driver sets the accuracy of every solve (coupling.fluid_accuracy);"
                        << " fsiDict coupled.residualDrop and coupled.forceTolerance are not used,"
                        << " coupled.maxIterations " << ctrl.maxIterations << " stays the cap" << endl;
                    announced = true;
                }
                const SolveResult r = solve(c.accuracyGiven ? askedControls(ctrl, c) : ctrl);
                if (c.accuracyGiven)
                {
                    Info<< "fsi: asked force tolerance " << c.forceTolerance << ", residual drop "
                        << c.residualDrop << ", at least " << c.minIterations << " iterations" << endl;
                }
                checkDiverged(r);
                ForceReport report;
                const vectorField f(faceForces(patchi_));
                report.faceForces = gatherFaceForces(f);
                report.simpleIterations = r.iterations;
                report.residuals = {r.residualU, r.residualP};
                report.converged = r.converged;
                const vector total = gSum(f);
                const scalar maxDisp = gMax(mag(displacement_)());
                Info<< "fsi: step " << c.step << " iteration " << c.iteration
                    << ": " << r.iterations << " SIMPLE iterations"
                    << (r.converged ? "" : " (cap reached)")
                    << ", residuals U " << r.residualU << " p " << r.residualP
                    << ", interface force " << total << " N" << endl;
                writeInterfaceCsv
                (
                    "interfaceForces_" + Foam::name(c.step) + "_" + Foam::name(c.iteration) + ".csv",
                    report.faceForces, nGlobalFaces_, "i,fx,fy,fz"
                );
                if (Pstream::master())
                {
                    logFile_()
                        << c.step << ',' << c.iteration << ',' << r.iterations << ','
                        << int(r.converged) << ',' << r.residualU << ',' << r.residualP << ','
                        << total.x() << ',' << total.y() << ',' << total.z() << ','
                        << maxDisp << ',' << wall.elapsedTime() << endl;
                }
                transport_->sendForces(c, report);
                break;
            }
            case CommandKind::accept:
            {
                Info<< "fsi: ACCEPT step " << c.step << " time " << c.time << endl;
                reportForces("accepted");
                writeLevel(c.time);
                if (Pstream::master())
                {
                    // Written after the fields: a listed level is complete on disk (restart).
                    OFstream
                    (
                        logDir/"accepted.csv",
                        IOstream::ASCII,
                        IOstream::currentVersion,
                        IOstream::UNCOMPRESSED,
                        true
                    )() << c.step << ',' << c.time << ',' << Time::timeName(c.time) << endl;
                }
                break;
            }
            case CommandKind::finish:
            {
                Info<< "fsi: FINISH after " << wall.elapsedTime() << " s" << endl;
                return 0;
            }
            case CommandKind::abort:
            {
                Perr<< "error: the solid side aborted: " << c.reason.c_str() << endl;
                return 2;
            }
        }
    }
}


std::unique_ptr<fsi::fluid::CouplingTransport>
Foam::fluidSolidCoupling::prescribedTransport(const dictionary& dict)
{
    fsi::fluid::PrescribedMotion m;
    m.type = dict.get<word>("type");
    if (m.type != "rotation" && m.type != "bending")
    {
        FatalIOErrorInFunction(dict)
            << "system/fsiDict: prescribed.type must be rotation or bending, got "
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
    return fsi::fluid::makePrescribedTransport(m);
}

// ************************************************************************* //
