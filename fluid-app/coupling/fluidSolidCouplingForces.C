// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: interface forces (see fluidSolidCoupling.H): per face, totals, and the check
// against functionObjects::forces.
#include "fluidSolidCoupling.H"

#include "forces.H"
#include "calculatedFvPatchField.H"

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


Foam::vector Foam::fluidSolidCoupling::addToForceBlocks
(
    const label iteration,
    const label blockLength
)
{
    const tmp<vectorField> f = faceForces(patchi_);
    if ((iteration - 1) % blockLength == 0)
    {
        // A new block: the one just completed becomes the previous one.
        previousBlockForces_ = currentBlockForces_;
        currentBlockForces_ = vectorField(f().size(), Zero);
        blockLength_ = blockLength;
    }
    const scalar w = fsi::fluid::SteadyConvergence::blockWeight(iteration, blockLength);
    currentBlockForces_ += w*f();
    if (sumFields_)
    {
        addToFieldBlocks(iteration, blockLength, w);
    }
    return gSum(f());
}


namespace
{
// A zero field shaped like `field`, calculated patches (constraint patches keep their type),
// not registered: a plain sum.
template<class Type>
Foam::autoPtr<Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>> zeroSum
(
    const Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& field
)
{
    using namespace Foam;
    return autoPtr<GeometricField<Type, fvPatchField, volMesh>>::New
    (
        IOobject(field.name() + "BlockSum", field.time().timeName(), field.mesh(),
                 IOobject::NO_READ, IOobject::NO_WRITE, false),
        field.mesh(),
        dimensioned<Type>(field.dimensions(), Zero),
        calculatedFvPatchField<Type>::typeName
    );
}

// sum += w field, internal and boundary values
template<class Type>
void addWeighted
(
    Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& sum,
    const Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& field,
    const Foam::scalar w
)
{
    sum.primitiveFieldRef() += w*field.primitiveField();
    forAll(sum.boundaryField(), patchi)
    {
        Foam::Field<Type>& b = sum.boundaryFieldRef()[patchi];
        b += w*field.boundaryField()[patchi];
    }
}

// field = (previous + current) / n, boundary values included (no evaluation)
template<class Type>
void assignMean
(
    Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& field,
    const Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& previous,
    const Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>& current,
    const Foam::scalar n
)
{
    field.primitiveFieldRef() = (previous.primitiveField() + current.primitiveField())/n;
    forAll(field.boundaryField(), patchi)
    {
        field.boundaryFieldRef()[patchi] ==
            (previous.boundaryField()[patchi] + current.boundaryField()[patchi])/n;
    }
}
} // namespace


void Foam::fluidSolidCoupling::startFieldBlocks()
{
    sumFields_ = true;
    scalarFields_.clear();
    scalarFields_.append(&p_);
    for (const word name : {"k", "omega", "nut", "nuTilda", "epsilon", "ReThetat", "gammaInt"})
    {
        if (mesh_.foundObject<volScalarField>(name))
        {
            scalarFields_.append(&mesh_.lookupObjectRef<volScalarField>(name));
        }
    }
    currentScalarSums_.clear();
    previousScalarSums_.clear();
    currentUSum_.reset(nullptr);
    previousUSum_.reset(nullptr);
}


void Foam::fluidSolidCoupling::addToFieldBlocks
(
    const label iteration,
    const label blockLength,
    const scalar w
)
{
    if ((iteration - 1) % blockLength == 0)
    {
        // a new block: the one just completed becomes the previous one
        previousUSum_ = std::move(currentUSum_);
        currentUSum_ = zeroSum(U_);
        previousScalarSums_.transfer(currentScalarSums_);
        currentScalarSums_.setSize(scalarFields_.size());
        forAll(scalarFields_, i)
        {
            currentScalarSums_.set(i, zeroSum(*scalarFields_[i]).ptr());
        }
    }
    addWeighted(currentUSum_(), U_, w);
    forAll(scalarFields_, i)
    {
        addWeighted(currentScalarSums_[i], *scalarFields_[i], w);
    }
}


void Foam::fluidSolidCoupling::useMeanFields()
{
    if (!sumFields_ || !previousUSum_.valid() || !currentUSum_.valid()
     || previousScalarSums_.size() != scalarFields_.size())
    {
        FatalErrorInFunction
            << "fsi: no two complete blocks of field sums: the band rule stopped before its "
            << "second block ended (a bug)" << exit(FatalError);
    }
    const scalar n = scalar(blockLength_);   // weights: n/2 per block
    assignMean(U_, previousUSum_(), currentUSum_(), n);
    wordList names(1, U_.name());
    forAll(scalarFields_, i)
    {
        assignMean(*scalarFields_[i], previousScalarSums_[i], currentScalarSums_[i], n);
        names.append(scalarFields_[i]->name());
    }
    Info<< "fsi: converged in the mean: the fields " << names << " are now the weighted mean of "
        << "the last " << 2*blockLength_ << " iterations; the loads below are the mean flow's"
        << endl;
}


Foam::tmp<Foam::vectorField> Foam::fluidSolidCoupling::meanBlockForces() const
{
    return tmp<vectorField>::New
    (
        (previousBlockForces_ + currentBlockForces_)/scalar(blockLength_)   // weights: n/2 each
    );
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

// ************************************************************************* //
