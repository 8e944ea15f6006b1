// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: interface forces (see fluidSolidCoupling.H): per face, totals, and the check
// against functionObjects::forces.
#include "fluidSolidCoupling.H"

#include "forces.H"

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
    currentBlockForces_ += fsi::fluid::SteadyConvergence::blockWeight(iteration, blockLength)*f();
    return gSum(f());
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
