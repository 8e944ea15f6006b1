// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: Anderson mixing of the SIMPLE iterations (see simpleAcceleration.H).
#include "simpleAcceleration.H"
#include "coupledPatches.H"

#include <algorithm>
#include <cmath>
#include <sstream>

Foam::simpleAcceleration::Settings Foam::simpleAcceleration::Settings::read
(
    const dictionary& simpleDict
)
{
    Settings s;
    if (!simpleDict.found("acceleration"))
    {
        return s;
    }
    const dictionary& d = simpleDict.subDict("acceleration");
    const word type(d.getOrDefault<word>("type", "none"));
    if (type != "none" && type != "anderson")
    {
        FatalIOErrorInFunction(d)
            << "system/fvSolution: SIMPLE.acceleration.type must be none or anderson, got '"
            << type << "'" << exit(FatalIOError);
    }
    s.anderson = (type == "anderson");
    s.depth = d.getOrDefault<label>("depth", s.depth);
    s.maxCoefficientSum = d.getOrDefault<scalar>("maxCoefficientSum", s.maxCoefficientSum);
    if (s.depth < 1 || s.depth > 50)
    {
        FatalIOErrorInFunction(d)
            << "system/fvSolution: SIMPLE.acceleration.depth must be in 1..50 (iterations"
            << " mixed; 5 is a good start), got " << s.depth << exit(FatalIOError);
    }
    if (!(s.maxCoefficientSum > 1 && s.maxCoefficientSum < 1e6))
    {
        FatalIOErrorInFunction(d)
            << "system/fvSolution: SIMPLE.acceleration.maxCoefficientSum must be in (1, 1e6),"
            << " e.g. 20, got " << s.maxCoefficientSum << exit(FatalIOError);
    }
    return s;
}


Foam::simpleAcceleration::simpleAcceleration
(
    const Settings& settings,
    volVectorField& U,
    volScalarField& p,
    surfaceScalarField& phi
)
:
    settings_(settings),
    U_(U),
    p_(p),
    phi_(phi)
{
    if (!settings_.anderson)
    {
        return;
    }
    mixer_.reset(new fsi::fluid::AndersonMixer(settings_.depth, settings_.maxCoefficientSum));
    for (const char* name : turbulenceFieldNames)
    {
        if (U_.mesh().foundObject<volScalarField>(name))
        {
            scalarNames_.append(word(name));
        }
    }
}


std::string Foam::simpleAcceleration::describe() const
{
    if (!active())
    {
        return "SIMPLE iterations not accelerated (fvSolution SIMPLE.acceleration type none)";
    }
    std::ostringstream os;
    os << "Anderson mixing of the SIMPLE iterations (fvSolution SIMPLE.acceleration): depth "
       << settings_.depth << ", restart above |gamma|_1 " << settings_.maxCoefficientSum
       << "; fields U p phi";
    for (const word& n : scalarNames_)
    {
        os << ' ' << n;
    }
    return os.str();
}


void Foam::simpleAcceleration::reset()
{
    mixed_ = 0;
    restarts_ = 0;
    if (mixer_)
    {
        mixer_->reset();
    }
}


std::size_t Foam::simpleAcceleration::packCells(std::vector<double>& s) const
{
    std::size_t k = 0;
    const vectorField& u = U_.primitiveField();
    for (direction c = 0; c < 3; ++c)
    {
        forAll(u, i)
        {
            s[k++] = u[i].component(c);
        }
    }
    for (const scalar v : p_.primitiveField())
    {
        s[k++] = v;
    }
    return k;
}


void Foam::simpleAcceleration::pack(std::vector<double>& s) const
{
    const label nC = U_.size();
    label nB = 0;
    forAll(phi_.boundaryField(), patchi)
    {
        nB += phi_.boundaryField()[patchi].size();
    }
    s.resize(std::size_t((4 + scalarNames_.size())*nC + phi_.size() + nB));
    std::size_t k = packCells(s);
    for (const word& name : scalarNames_)
    {
        for (const scalar v : U_.mesh().lookupObject<volScalarField>(name).primitiveField())
        {
            s[k++] = v;
        }
    }
    for (const scalar v : phi_.primitiveField())
    {
        s[k++] = v;
    }
    forAll(phi_.boundaryField(), patchi)
    {
        for (const scalar v : phi_.boundaryField()[patchi])
        {
            s[k++] = v;
        }
    }
}


void Foam::simpleAcceleration::unpack(const std::vector<double>& s)
{
    std::size_t k = 0;
    vectorField& u = U_.primitiveFieldRef();
    for (direction c = 0; c < 3; ++c)
    {
        forAll(u, i)
        {
            u[i].component(c) = s[k++];
        }
    }
    for (scalar& v : p_.primitiveFieldRef())
    {
        v = s[k++];
    }
    for (const word& name : scalarNames_)
    {
        volScalarField& f = U_.mesh().lookupObjectRef<volScalarField>(name);
        scalarField& values = f.primitiveFieldRef();
        // non-negative: at least half the plain iteration's value (state_ holds it)
        const std::size_t plain = k;
        forAll(values, i)
        {
            values[i] = std::max(s[k], 0.5*state_[plain + std::size_t(i)]);
            ++k;
        }
        if (name == "gammaInt")
        {
            values = min(values, scalar(1));
        }
        evaluateCoupledPatches(f);
    }
    for (scalar& v : phi_.primitiveFieldRef())
    {
        v = s[k++];
    }
    auto& phib = phi_.boundaryFieldRef();
    forAll(phib, patchi)
    {
        for (scalar& v : phib[patchi])
        {
            v = s[k++];
        }
    }
    U_.correctBoundaryConditions();
    p_.correctBoundaryConditions();
}


void Foam::simpleAcceleration::beforeIteration()
{
    if (!mixer_)
    {
        return;
    }
    // only the measured part (U, p in the cells): the residual G(x) - x needs no more of x
    start_.resize(std::size_t(4*U_.size()));
    packCells(start_);
}


fsi::fluid::AndersonMixer::Step Foam::simpleAcceleration::afterIteration()
{
    if (!mixer_)
    {
        return {};
    }
    pack(state_);
    // measured residual: U and p in the cells, scaled
    const std::size_t nC = std::size_t(U_.size());
    const scalar uRef = max(gMax(mag(U_.primitiveField())), SMALL);
    residual_.resize(4*nC);
    for (std::size_t i = 0; i < 3*nC; ++i)
    {
        residual_[i] = (state_[i] - start_[i])/uRef;
    }
    for (std::size_t i = 3*nC; i < 4*nC; ++i)
    {
        residual_[i] = (state_[i] - start_[i])/(uRef*uRef);
    }
    mixedState_ = state_;   // state_ keeps the plain values (unpack bounds the turbulence fields)
    const fsi::fluid::AndersonMixer::Step step = mixer_->mix
    (
        mixedState_,
        residual_,
        [](std::vector<double>& v)
        {
            scalarField sums(label(v.size()));
            std::copy(v.begin(), v.end(), sums.begin());
            reduce(sums, sumOp<scalarField>());
            std::copy(sums.begin(), sums.end(), v.begin());
        }
    );
    if (step.restarted)
    {
        ++restarts_;
    }
    if (step.columns > 0)
    {
        ++mixed_;
        unpack(mixedState_);
    }
    return step;
}

// ************************************************************************* //
