// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: interface motion and the mesh-quality guard (see fluidSolidCoupling.H).
#include "fluidSolidCoupling.H"

#include "fvc.H"
#include "pointFields.H"
#include "valuePointPatchFields.H"
#include "fixedValuePointPatchFields.H"
#include "slipPointPatchFields.H"
#include "syncTools.H"
#include "polyMeshTools.H"
#include "unitConversion.H"
#include "clockTime.H"

namespace
{

// Deletes the registry-owned fields of type FieldType named grad(...): the gradients that
// fvSolution's 'cache' entry keeps between calls (e.g. grad(U), computed for the interface
// force at the end of a SIMPLE iteration and reused by the next momentum equation).
template<class FieldType>
void dropCachedGradients(Foam::fvMesh& mesh)
{
    Foam::HashTable<FieldType*> fields(mesh.lookupClass<FieldType>());
    forAllIters(fields, iter)
    {
        FieldType* field = iter.val();
        if (field->ownedByRegistry() && field->name().compare(0, 5, "grad(") == 0)
        {
            delete field;   // checks itself out of the registry, as gradScheme does
        }
    }
}

} // End anonymous namespace


void Foam::fluidSolidCoupling::moveInterface
(
    const std::vector<double>& localDisplacement
)
{
    forAll(displacement_, i)
    {
        displacement_[i] = vector
        (
            localDisplacement[3*i],
            localDisplacement[3*i + 1],
            localDisplacement[3*i + 2]
        );
    }

    pointVectorField* pdPtr =
        mesh_.lookupObjectRefPtr<pointVectorField>("pointDisplacement");
    if (!pdPtr)
    {
        failWith
        (
            "no pointDisplacement field: constant/dynamicMeshDict must select "
            "dynamicMotionSolverFvMesh with a displacement solver "
            "(displacementLaplacian, fsiInverseDistance)"
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
    keepInterfaceOnSlipWalls();
    refCast<valuePointPatchVectorField>(ppf) == displacement_;

    // warmStart flux kept: the flux through each face from U before the motion (below)
    autoPtr<surfaceScalarField> fluxBefore;
    if (warmStart_.settings().keepFlux)
    {
        fluxBefore.reset(new surfaceScalarField("fluxBeforeMotion", fvc::flux(U_)));
    }

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

    // Steady, no mesh-flux terms. interpolated (default): phi = the flux of U on the moved
    // faces. kept: the last pressure equation's flux (mass conserving, with its pressure
    // smoothing part) plus the change of U's flux over the moved faces, so that a converged
    // flow stays converged when nothing moved (flowWarmStart.H).
    if (fluxBefore.valid())
    {
        phi_ += fvc::flux(U_) - fluxBefore();
    }
    else
    {
        phi_ = fvc::flux(U_);
    }

    // The mesh now stands still until the next interface motion. Refresh the one piece of
    // geometry that is only updated while the mesh is flagged moving (the turbulence model's
    // near-wall distances, used by wall functions), then clear the flag: left set, every SIMPLE
    // iteration of the steady solve recomputes those distances (turbulenceModel::correct):
    // about a sixth of the fluid's CPU time in the coupled hydrofoil, for results that are
    // identical to the last bit.
    const_cast<nearWallDist&>(turbulence_.y()).correct();
    mesh_.moving(false);
    // Gradients cached through fvSolution's 'cache' belong to the old geometry. OpenFOAM drops
    // them only while the mesh is flagged moving.
    dropCachedGradients<volVectorField>(mesh_);
    dropCachedGradients<volTensorField>(mesh_);
}


void Foam::fluidSolidCoupling::keepInterfaceOnSlipWalls()
{
    forAll(displacement_, i)
    {
        displacement_[i] -= (displacement_[i] & slipNormals_[i])*slipNormals_[i];
    }
}


Foam::vectorField Foam::fluidSolidCoupling::slipWallNormals(const pointField& allPoints0) const
{
    const labelList& meshPoints = mesh_.boundaryMesh()[patchi_].meshPoints();
    vectorField normals(meshPoints.size(), Zero);
    const pointVectorField* pd = mesh_.findObject<pointVectorField>("pointDisplacement");
    if (!pd)
    {
        return normals;   // no mesh motion (moveInterface says so if it is asked to move)
    }
    // area vectors of the slip walls' faces at their points, summed over the ranks that share
    // a point
    vectorField area(mesh_.nPoints(), Zero);
    wordList walls;
    forAll(pd->boundaryField(), patchi)
    {
        if (patchi == patchi_ || !isA<slipPointPatchVectorField>(pd->boundaryField()[patchi]))
        {
            continue;
        }
        walls.append(mesh_.boundaryMesh()[patchi].name());
        for (const face& f : mesh_.boundaryMesh()[patchi])
        {
            const vector a(f.areaNormal(allPoints0));
            for (const label pointi : f)
            {
                area[pointi] += a;
            }
        }
    }
    syncTools::syncPointList(mesh_, area, plusEqOp<vector>(), vector::zero);
    label onWall = 0;
    forAll(meshPoints, i)
    {
        const vector& a = area[meshPoints[i]];
        if (mag(a) > VSMALL)
        {
            normals[i] = a/mag(a);
            ++onWall;
        }
    }
    reduce(onWall, sumOp<label>());   // a point shared by ranks counts on each
    Info<< "fsi: " << onWall << " interface point entries lie on slip walls " << walls
        << ": they keep to the wall (the displacement along its normal is dropped)" << endl;
    return normals;
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

// ************************************************************************* //
