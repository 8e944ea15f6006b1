// SPDX-License-Identifier: GPL-3.0-or-later
// fsiInverseDistance mesh motion (see fsiInverseDistanceMotionSolver.H).
#include "fsiInverseDistanceMotionSolver.H"

#include "addToRunTimeSelectionTable.H"
#include "ListListOps.H"
#include "pointFields.H"
#include "syncTools.H"
#include "valuePointPatchFields.H"
#include "cpuTime.H"

namespace Foam
{
    defineTypeNameAndDebug(fsiInverseDistanceMotionSolver, 0);
    addToRunTimeSelectionTable(motionSolver, fsiInverseDistanceMotionSolver, dictionary);
    addToRunTimeSelectionTable
    (
        displacementMotionSolver,
        fsiInverseDistanceMotionSolver,
        displacement
    );
}

namespace
{

// Every rank's list, concatenated in rank order, on every rank
template<class T>
Foam::Field<T> allGathered(const Foam::Field<T>& local)
{
    Foam::List<Foam::Field<T>> all(Foam::Pstream::nProcs());
    all[Foam::Pstream::myProcNo()] = local;
    Foam::Pstream::gatherList(all);
    Foam::Pstream::scatterList(all);
    return Foam::ListListOps::combine<Foam::Field<T>>(all, Foam::accessOp<Foam::Field<T>>());
}

// Unit normals of a patch's points: the sum of the adjacent faces' area vectors
Foam::vectorField pointNormals
(
    const Foam::faceList& localFaces,
    const Foam::pointField& localPoints
)
{
    Foam::vectorField n(localPoints.size(), Foam::Zero);
    for (const Foam::face& f : localFaces)
    {
        const Foam::vector a(f.areaNormal(localPoints));
        for (const Foam::label pointi : f)
        {
            n[pointi] += a;
        }
    }
    return n/(Foam::mag(n) + Foam::VSMALL);
}

// F = K P^-1 (the least-squares affine map of a patch point's neighbourhood); the identity
// if P is singular (degenerate neighbourhood)
Foam::tensor affineMap(const Foam::tensor& K, const Foam::tensor& P)
{
    if (!(Foam::det(P) > Foam::SMALL*Foam::pow3(Foam::tr(P))))
    {
        return Foam::I;
    }
    return K & Foam::inv(P);
}

} // End anonymous namespace


Foam::fsiInverseDistanceMotionSolver::fsiInverseDistanceMotionSolver
(
    const polyMesh& mesh,
    const IOdictionary& dict
)
:
    displacementMotionSolver(mesh, dict, typeName)
{
    readCoeffs();
    collectSources();
}


Foam::fsiInverseDistanceMotionSolver::fsiInverseDistanceMotionSolver
(
    const polyMesh& mesh,
    const IOdictionary& dict,
    const pointVectorField& pointDisplacement,
    const pointIOField& points0
)
:
    displacementMotionSolver(mesh, dict, pointDisplacement, points0, typeName)
{
    readCoeffs();
    collectSources();
}


void Foam::fsiInverseDistanceMotionSolver::readCoeffs()
{
    const word where("constant/dynamicMeshDict " + typeName + "Coeffs");
    const wordList names(coeffDict().get<wordList>("patches"));
    patchIDs_.setSize(names.size());
    forAll(names, i)
    {
        patchIDs_[i] = mesh().boundaryMesh().findPatchID(names[i]);
        if (patchIDs_[i] < 0)
        {
            FatalErrorInFunction
                << where << ": patches: no patch '" << names[i]
                << "' in the mesh; list the moving patches" << exit(FatalError);
        }
    }
    decayDistance_ = coeffDict().get<scalar>("decayDistance");
    if (!(decayDistance_ > 0))
    {
        FatalErrorInFunction
            << where << ": decayDistance " << decayDistance_
            << " must be positive (m): the distance from the patches at which motion stops"
            << exit(FatalError);
    }
    affineDistance_ = coeffDict().getOrDefault<scalar>("affineDistance", 0.1*decayDistance_);
    if (!(affineDistance_ > 0))
    {
        FatalErrorInFunction
            << where << ": affineDistance " << affineDistance_
            << " must be positive (m): the reach of each patch point's affine part"
            << exit(FatalError);
    }
    exponent_ = coeffDict().getOrDefault<label>("exponent", 5);
    if (exponent_ < 2 || exponent_ > 5)
    {
        FatalErrorInFunction
            << where << ": exponent " << exponent_ << " must be 2, 3, 4 or 5" << exit(FatalError);
    }
    openingAngle_ = coeffDict().getOrDefault<scalar>("openingAngle", 0);
    if (!(openingAngle_ >= 0 && openingAngle_ < 1))
    {
        FatalErrorInFunction
            << where << ": openingAngle " << openingAngle_ << " must be in [0, 1): 0 sums every"
            << " patch point exactly, 0.1 to 0.3 expands far clusters of them"
            << exit(FatalError);
    }
}


void Foam::fsiInverseDistanceMotionSolver::collectSources()
{
    DynamicList<point> pts;
    DynamicList<scalar> areas;
    onMovingPatch_.setSize(mesh().nPoints(), false);
    normals0_.setSize(patchIDs_.size());
    forAll(patchIDs_, k)
    {
        const polyPatch& pp = mesh().boundaryMesh()[patchIDs_[k]];
        const labelList& meshPoints = pp.meshPoints();
        UIndirectList<bool>(onMovingPatch_, meshPoints) = true;
        const pointField localPoints0(points0(), meshPoints);
        normals0_[k] = pointNormals(pp.localFaces(), localPoints0);
        scalarField pointArea(meshPoints.size(), Zero);
        for (const face& f : pp.localFaces())
        {
            const scalar share = f.mag(localPoints0)/f.size();
            for (const label pointi : f)
            {
                pointArea[pointi] += share;
            }
        }
        pts.append(localPoints0);
        areas.append(pointArea);
    }
    onMovingPatchAnyRank_ = onMovingPatch_;
    syncTools::syncPointList(mesh(), onMovingPatchAnyRank_, orEqOp<bool>(), false);
    sourcePoints0_ = allGathered(pointField(pts));
    sourceAreas_ = allGathered(scalarField(areas));
    if (sourcePoints0_.empty())
    {
        FatalErrorInFunction
            << "constant/dynamicMeshDict " << typeName << "Coeffs: the moving patches have no "
            << "points" << exit(FatalError);
    }
    reach_ = boundBox(sourcePoints0_, false);
    reach_.min() -= vector::uniform(decayDistance_);
    reach_.max() += vector::uniform(decayDistance_);
    tree_.reset
    (
        new inverseDistanceTree(sourcePoints0_, sourceAreas_, exponent_, openingAngle_)
    );
    Info<< typeName << ": " << sourcePoints0_.size() << " moving patch points ("
        << tree_->nNodes() << " tree nodes), decay distance " << decayDistance_
        << " m, affine reach " << affineDistance_ << " m, exponent " << exponent_
        << ", opening angle " << openingAngle_
        << (openingAngle_ > 0 ? "" : " (exact sums)") << endl;
}


void Foam::fsiInverseDistanceMotionSolver::gatherSourceMotions
(
    vectorField& translation,
    tensorField& affineMinusI
) const
{
    DynamicList<vector> t;
    DynamicList<tensor> m;
    forAll(patchIDs_, k)
    {
        const label patchi = patchIDs_[k];
        const pointPatchVectorField& ppf = pointDisplacement_.boundaryField()[patchi];
        if (!isA<valuePointPatchVectorField>(ppf))
        {
            FatalErrorInFunction
                << "0/pointDisplacement: patch " << ppf.patch().name() << " moves the mesh ("
                << typeName << ") and must be fixedValue, is " << ppf.type()
                << exit(FatalError);
        }
        const vectorField d(refCast<const valuePointPatchVectorField>(ppf));
        const polyPatch& pp = mesh().boundaryMesh()[patchi];
        const pointField p0(points0(), pp.meshPoints());
        const pointField p1(p0 + d);
        const vectorField& n0 = normals0_[k];
        const vectorField n1(pointNormals(pp.localFaces(), p1));
        const edgeList& edges = pp.edges();
        const labelListList& pointEdges = pp.pointEdges();
        forAll(p0, i)
        {
            // The local affine map F = K P^-1 that best maps the reference edges p_j to the
            // moved ones q_j (least squares), K = sum q_j p_j^T, P = sum p_j p_j^T, over the
            // edge neighbours j plus the unit normals (reference to moved), scaled by the
            // mean squared edge length: a patch's edges leave its normal direction open
            tensor K(Zero);
            tensor P(Zero);
            scalar meanEdge2 = 0;
            for (const label e : pointEdges[i])
            {
                const label j = edges[e].otherVertex(i);
                const vector p(p0[j] - p0[i]);
                K += (p1[j] - p1[i])*p;
                P += p*p;
                meanEdge2 += magSqr(p);
            }
            meanEdge2 /= max(pointEdges[i].size(), 1);
            K += meanEdge2*(n1[i]*n0[i]);
            P += meanEdge2*(n0[i]*n0[i]);
            t.append(d[i]);
            m.append(affineMap(K, P) - I);
        }
    }
    translation = allGathered(vectorField(t));
    affineMinusI = allGathered(tensorField(m));
}


Foam::tmp<Foam::pointField> Foam::fsiInverseDistanceMotionSolver::curPoints() const
{
    tmp<pointField> tcurPoints(points0() + pointDisplacement_.primitiveField());
    twoDCorrectPoints(tcurPoints.ref());
    return tcurPoints;
}


void Foam::fsiInverseDistanceMotionSolver::solve()
{
    pointDisplacement_.boundaryFieldRef().updateCoeffs();
    vectorField t;
    tensorField m;
    gatherSourceMotions(t, m);
    tree_->setTranslations(t);
    // the affine part M_i (x - x_i) = M_i x - c_i
    const vectorField c(m & sourcePoints0_);

    const cpuTime clock;
    label inReach = 0;
    label expansions = 0;
    const pointField& x0 = points0();
    const scalar D2 = sqr(decayDistance_);
    const scalar L2 = sqr(affineDistance_);
    vectorField& d = pointDisplacement_.primitiveFieldRef();
    forAll(x0, pointi)
    {
        if (onMovingPatch_[pointi])
        {
            continue;   // set by the patch's fixedValue below
        }
        const point& x = x0[pointi];
        scalar r2Min = GREAT;
        const label nearest = reach_.contains(x) ? tree_->nearest(x, r2Min) : -1;
        if (r2Min >= D2)
        {
            d[pointi] = Zero;   // beyond the decay distance of every patch point
            continue;
        }
        if (r2Min < sqr(SMALL*decayDistance_))
        {
            d[pointi] = t[nearest];   // on a patch point (another rank's)
            continue;
        }
        ++inReach;
        scalar weight = 0;
        vector sumT(Zero);      // sum of w t_i
        vector sumC(Zero);      // sum of w g c_i
        tensor sumM(Zero);      // sum of w g M_i
        expansions += tree_->sum
        (
            x, affineDistance_, weight, sumT,
            [&](const label i, const scalar r2, const scalar w)
            {
                if (r2 < L2)
                {
                    const scalar g = sqr(1 - r2/L2);
                    sumM += (w*g)*m[i];
                    sumC += (w*g)*c[i];
                }
            }
        );
        const scalar s = sqrt(r2Min/D2);
        d[pointi] = (1 - s*s*(3 - 2*s))*(sumT - sumC + (sumM & x))/weight;
    }
    pointDisplacement_.correctBoundaryConditions();
    synchroniseSharedPoints();
    Info<< typeName << ": " << returnReduce(inReach, sumOp<label>()) << " points within the"
        << " decay distance, " << returnReduce(expansions, sumOp<label>())
        << " cluster expansions, " << returnReduce(clock.elapsedCpuTime(), maxOp<scalar>())
        << " s" << endl;
}


void Foam::fsiInverseDistanceMotionSolver::synchroniseSharedPoints()
{
    if (!Pstream::parRun())
    {
        return;
    }
    // The boundary conditions were applied rank by rank: a slip wall projects with the point
    // normals of this rank's own faces of the moved geometry, and a point of a moving patch
    // may lie on that patch on one rank only. So a point on a processor boundary can end up
    // with two displacements (on the hydrofoil's boundary-layer mesh: the root-wall points next
    // to the trailing edge, 1e-6 m apart, after the second motion), and the processor faces no
    // longer match. Every rank takes the same value: a moving patch's value where the point
    // lies on a moving patch on any rank, else the larger of the ranks' values.
    const polyMesh& m = mesh();
    vectorField& d = pointDisplacement_.primitiveFieldRef();
    vectorField patchValue(m.nPoints(), vector::uniform(-GREAT));
    for (const label patchi : patchIDs_)
    {
        const vectorField values
        (
            refCast<const valuePointPatchVectorField>(pointDisplacement_.boundaryField()[patchi])
        );
        UIndirectList<vector>(patchValue, m.boundaryMesh()[patchi].meshPoints()) = values;
    }
    syncTools::syncPointList(m, patchValue, maxEqOp<vector>(), vector::uniform(-GREAT));
    syncTools::syncPointList(m, d, maxMagSqrEqOp<vector>(), vector::zero);
    forAll(onMovingPatchAnyRank_, pointi)
    {
        if (onMovingPatchAnyRank_[pointi])
        {
            d[pointi] = patchValue[pointi];
        }
    }
}
