// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: where a driver's SOLVE starts (see flowWarmStart.H).
#include "flowWarmStart.H"
#include "fvcFlux.H"
#include "coupledPatches.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>
#include <vector>

// The turbulence fields (coupledPatches.H) are extrapolated with the flow when present. A
// turbulence field's wall function can only be evaluated inside correct(), so extrapolated
// turbulence fields update their processor patches only (evaluateCoupledPatches): evaluating
// all of them failed with "request for volScalarField::Internal kOmegaSST:G failed" at the
// coupled run's third solve, the first extrapolated one.


Foam::flowWarmStart::Settings Foam::flowWarmStart::Settings::read
(
    const dictionary& coupledDict,
    const fileName& source
)
{
    Settings s;
    if (!coupledDict.found("warmStart"))
    {
        return s;
    }
    const dictionary& d = coupledDict.subDict("warmStart");
    const word type(d.getOrDefault<word>("type", "previous"));
    if (type != "previous" && type != "secant")
    {
        FatalIOErrorInFunction(d)
            << source << ": coupled.warmStart.type must be previous or secant, got '" << type
            << "'" << exit(FatalIOError);
    }
    s.secant = (type == "secant");
    const word flux(d.getOrDefault<word>("flux", "interpolated"));
    if (flux != "interpolated" && flux != "kept")
    {
        FatalIOErrorInFunction(d)
            << source << ": coupled.warmStart.flux must be interpolated or kept, got '" << flux
            << "'" << exit(FatalIOError);
    }
    s.keepFlux = (flux == "kept");
    s.snapshots = d.getOrDefault<label>("snapshots", s.snapshots);
    s.maxCoefficient = d.getOrDefault<scalar>("maxCoefficient", s.maxCoefficient);
    s.minNewDirection = d.getOrDefault<scalar>("minNewDirection", s.minNewDirection);
    if (s.snapshots < 2)
    {
        FatalIOErrorInFunction(d)
            << source << ": coupled.warmStart.snapshots must be >= 2 (the newest flow and at"
            << " least one to differ from), got " << s.snapshots << exit(FatalIOError);
    }
    if (!(s.maxCoefficient > 0))
    {
        FatalIOErrorInFunction(d)
            << source << ": coupled.warmStart.maxCoefficient must be > 0, got "
            << s.maxCoefficient << exit(FatalIOError);
    }
    if (!(s.minNewDirection > 0 && s.minNewDirection < 1))
    {
        FatalIOErrorInFunction(d)
            << source << ": coupled.warmStart.minNewDirection must be in (0, 1), got "
            << s.minNewDirection << exit(FatalIOError);
    }
    return s;
}


Foam::flowWarmStart::flowWarmStart(const fvMesh& mesh, const Settings& settings)
:
    mesh_(mesh),
    settings_(settings),
    scalarNames_(1, word("p"))
{
    for (const char* name : turbulenceFieldNames)
    {
        if (mesh_.foundObject<volScalarField>(name))
        {
            scalarNames_.append(word(name));
        }
    }
}


Foam::volVectorField& Foam::flowWarmStart::U() const
{
    return mesh_.lookupObjectRef<volVectorField>("U");
}


Foam::volScalarField& Foam::flowWarmStart::scalarField(const word& name) const
{
    return mesh_.lookupObjectRef<volScalarField>(name);
}


Foam::surfaceScalarField& Foam::flowWarmStart::phi() const
{
    return mesh_.lookupObjectRef<surfaceScalarField>("phi");
}


Foam::string Foam::flowWarmStart::describe() const
{
    const char* flux = settings_.keepFlux ? "flux kept" : "flux interpolated";
    if (!settings_.secant)
    {
        return string("warm start: previous (each SOLVE starts from the last solve's flow), ")
             + flux;
    }
    OStringStream s;
    s << "warm start: secant (the flow extrapolated along the last " << settings_.snapshots
      << " solves' interface changes; fields U" << (settings_.keepFlux ? " phi" : "");
    forAll(scalarNames_, i)
    {
        s << " " << scalarNames_[i];
    }
    s << "; max |c| " << settings_.maxCoefficient << ", min new direction "
      << settings_.minNewDirection << "), " << flux;
    return s.str();
}


void Foam::flowWarmStart::record(const vectorField& displacement)
{
    if (!settings_.secant)
    {
        return;
    }
    Snapshot s;
    s.displacement = displacement;
    s.U = U().primitiveField();
    if (settings_.keepFlux)
    {
        const surfaceScalarField& flux = phi();
        s.phi = flux.primitiveField();
        s.phiPatches.setSize(flux.boundaryField().size());
        forAll(flux.boundaryField(), patchi)
        {
            s.phiPatches.set(patchi, new Foam::scalarField(flux.boundaryField()[patchi]));
        }
    }
    s.scalars.setSize(scalarNames_.size());
    forAll(scalarNames_, i)
    {
        s.scalars.set(i, new Foam::scalarField(scalarField(scalarNames_[i]).primitiveField()));
    }
    snapshots_.push_front(std::move(s));
    while (label(snapshots_.size()) > settings_.snapshots)
    {
        snapshots_.pop_back();
    }
}


namespace
{

const char* const snapshotFileTag = "fsi-toolkit warm-start snapshots v1";

template<class T>
void writeList(std::ofstream& os, const Foam::UList<T>& list)
{
    const std::int64_t n = list.size();
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    os.write(reinterpret_cast<const char*>(list.cdata()), std::streamsize(n*sizeof(T)));
}

template<class T>
bool readList(std::ifstream& is, Foam::List<T>& list, const Foam::label expected)
{
    std::int64_t n = -1;
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!is || n != expected)
    {
        return false;
    }
    list.setSize(Foam::label(n));
    is.read(reinterpret_cast<char*>(list.data()), std::streamsize(n*sizeof(T)));
    return bool(is);
}

} // namespace


void Foam::flowWarmStart::write(const fileName& file) const
{
    if (!settings_.secant)
    {
        return;
    }
    mkDir(file.path());
    const fileName tmp(file + ".tmp");
    {
        std::ofstream os(tmp.c_str(), std::ios::binary | std::ios::trunc);
        os << snapshotFileTag << '\n' << label(settings_.keepFlux) << ' ' << scalarNames_.size();
        for (const word& name : scalarNames_)
        {
            os << ' ' << name;
        }
        os << ' ' << label(snapshots_.size()) << '\n';
        for (const Snapshot& s : snapshots_)
        {
            writeList(os, s.displacement);
            writeList(os, s.U);
            if (settings_.keepFlux)
            {
                writeList(os, s.phi);
                forAll(s.phiPatches, patchi)
                {
                    writeList(os, s.phiPatches[patchi]);
                }
            }
            forAll(s.scalars, i)
            {
                writeList(os, s.scalars[i]);
            }
        }
        if (!os)
        {
            FatalErrorInFunction
                << "could not write the warm-start snapshots to " << tmp << exit(FatalError);
        }
    }
    if (std::rename(tmp.c_str(), file.c_str()) != 0)
    {
        FatalErrorInFunction
            << "could not rename " << tmp << " to " << file << exit(FatalError);
    }
}


bool Foam::flowWarmStart::read
(
    const fileName& file,
    const label nInterfacePoints,
    string& why
)
{
    snapshots_.clear();
    std::ifstream is(file.c_str(), std::ios::binary);
    if (!is)
    {
        why = "no " + file;
        return false;
    }
    std::string tag;
    std::getline(is, tag);
    if (!is || tag != snapshotFileTag)
    {
        why = file + " is not a warm-start snapshot file of this version";
        return false;
    }
    label keepFlux = -1, nScalars = -1, nSnapshots = -1;
    is >> keepFlux >> nScalars;
    if (!is || nScalars != scalarNames_.size())
    {
        why = file + " was written with other warm-start settings or fields";
        return false;
    }
    wordList names(nScalars);
    for (word& name : names)
    {
        is >> name;
    }
    is >> nSnapshots;
    is.get();   // the newline
    if (!is || bool(keepFlux) != settings_.keepFlux || names != scalarNames_ || nSnapshots < 0)
    {
        why = file + " was written with other warm-start settings or fields";
        return false;
    }
    const surfaceScalarField& flux = phi();
    for (label k = 0; k < nSnapshots; ++k)
    {
        Snapshot s;
        bool ok = readList(is, s.displacement, nInterfacePoints);
        ok = ok && readList(is, s.U, mesh_.nCells());
        if (ok && settings_.keepFlux)
        {
            ok = readList(is, s.phi, mesh_.nInternalFaces());
            s.phiPatches.setSize(flux.boundaryField().size());
            forAll(s.phiPatches, patchi)
            {
                s.phiPatches.set(patchi, new Foam::scalarField());
                ok = ok && readList(is, s.phiPatches[patchi], flux.boundaryField()[patchi].size());
            }
        }
        s.scalars.setSize(scalarNames_.size());
        forAll(s.scalars, i)
        {
            s.scalars.set(i, new Foam::scalarField());
            ok = ok && readList(is, s.scalars[i], mesh_.nCells());
        }
        if (!ok)
        {
            snapshots_.clear();
            why = file + " does not match this mesh (interface points, cells or faces) or is"
                " truncated";
            return false;
        }
        snapshots_.push_back(std::move(s));
    }
    while (label(snapshots_.size()) > settings_.snapshots)   // fewer kept now than then
    {
        snapshots_.pop_back();
    }
    return true;
}


Foam::flowWarmStart::Prediction Foam::flowWarmStart::predict(const vectorField& displacement)
{
    Prediction result;
    if (!settings_.secant)
    {
        result.reason = "type previous";
        return result;
    }
    if (snapshots_.size() < 2)
    {
        result.reason = "fewer than two earlier solves";
        return result;
    }
    const Snapshot& newest = snapshots_.front();
    const vectorField change(displacement - newest.displacement);
    const scalar changeNorm = Foam::sqrt(gSum(magSqr(change)));
    if (!(changeNorm > 0))
    {
        result.reason = "the interface did not move";
        return result;
    }

    // The columns d_j - d_0, longest first: a level's first solve is modelled mainly by the
    // last level's whole step, not by that level's last small correction (whose flow
    // difference is mostly the solves' own convergence error).
    std::vector<std::pair<scalar, label>> order;   // (length, snapshot index)
    for (label j = 1; j < label(snapshots_.size()); ++j)
    {
        const scalar length =
            Foam::sqrt(gSum(magSqr(snapshots_[j].displacement - newest.displacement)));
        if (length > 0)
        {
            order.emplace_back(length, j);
        }
    }
    std::stable_sort
    (
        order.begin(), order.end(),
        [](const std::pair<scalar, label>& a, const std::pair<scalar, label>& b)
        { return a.first > b.first; }
    );

    // Modified Gram-Schmidt in that order: Q (kept directions), R.
    std::vector<label> kept;           // snapshot index of each kept column
    PtrList<vectorField> q;
    std::vector<std::vector<scalar>> r;   // r[k][i]: column k's component along q_i, i <= k
    for (const auto& entry : order)
    {
        const label j = entry.second;
        const scalar length = entry.first;
        vectorField v(snapshots_[j].displacement - newest.displacement);
        std::vector<scalar> column;
        forAll(q, i)
        {
            const scalar a = gSum(q[i] & v);
            v -= a*q[i];
            column.push_back(a);
        }
        const scalar rest = Foam::sqrt(gSum(magSqr(v)));
        if (rest < settings_.minNewDirection*length)
        {
            continue;
        }
        column.push_back(rest);
        q.append(new vectorField(v/rest));
        r.push_back(column);
        kept.push_back(j);
    }
    label m = label(kept.size());
    result.columns = m;
    if (m == 0)
    {
        result.reason = "no usable earlier interface change";
        return result;
    }

    // R c = Q^T (d - d_0) over the first m columns (the leading block of R: the least-squares
    // solution for those columns alone); the most columns whose coefficients stay within
    // maxCoefficient. Nearly parallel columns need large coefficients of both signs: then the
    // shortest ones are left out.
    std::vector<scalar> rhs(m);
    for (label i = 0; i < m; ++i)
    {
        rhs[i] = gSum(q[i] & change);
    }
    std::vector<scalar> c;
    for (label used = m; used >= 1; --used)
    {
        c.assign(used, 0);
        for (label i = used - 1; i >= 0; --i)
        {
            scalar s = rhs[i];
            for (label k = i + 1; k < used; ++k)
            {
                s -= r[k][i]*c[k];
            }
            c[i] = s/r[i][i];
        }
        result.largestCoefficient = 0;
        for (const scalar ci : c)
        {
            result.largestCoefficient = max(result.largestCoefficient, mag(ci));
        }
        if (result.largestCoefficient <= settings_.maxCoefficient)
        {
            break;
        }
    }
    if (result.largestCoefficient > settings_.maxCoefficient)
    {
        result.reason = "a coefficient above maxCoefficient";
        return result;
    }
    m = label(c.size());
    result.columns = m;
    scalar capturedSq = 0;
    for (label i = 0; i < m; ++i)
    {
        capturedSq += rhs[i]*rhs[i];
    }
    result.captured = Foam::sqrt(capturedSq)/changeNorm;

    // q_start = q_0 + sum_j c_j (q_j - q_0)
    volVectorField& u = U();
    vectorField uStart(newest.U);
    for (label k = 0; k < m; ++k)
    {
        uStart += c[k]*(snapshots_[kept[k]].U - newest.U);
    }
    u.primitiveFieldRef() = uStart;
    u.correctBoundaryConditions();
    if (settings_.keepFlux)
    {
        surfaceScalarField& flux = phi();
        Foam::scalarField phiStart(newest.phi);
        for (label k = 0; k < m; ++k)
        {
            phiStart += c[k]*(snapshots_[kept[k]].phi - newest.phi);
        }
        flux.primitiveFieldRef() = phiStart;
        surfaceScalarField::Boundary& fluxPatches = flux.boundaryFieldRef();
        forAll(fluxPatches, patchi)
        {
            const Foam::scalarField& f0 = newest.phiPatches[patchi];
            Foam::scalarField start(f0);
            for (label k = 0; k < m; ++k)
            {
                start += c[k]*(snapshots_[kept[k]].phiPatches[patchi] - f0);
            }
            fluxPatches[patchi] == start;
        }
    }
    else
    {
        phi() = fvc::flux(u);
    }
    forAll(scalarNames_, i)
    {
        volScalarField& f = scalarField(scalarNames_[i]);
        const Foam::scalarField& f0 = newest.scalars[i];
        Foam::scalarField start(f0);
        for (label k = 0; k < m; ++k)
        {
            start += c[k]*(snapshots_[kept[k]].scalars[i] - f0);
        }
        if (i > 0)   // turbulence fields: non-negative, at least half the newest value
        {
            start = max(start, 0.5*f0);
            if (scalarNames_[i] == "gammaInt")
            {
                start = min(start, scalar(1));
            }
        }
        f.primitiveFieldRef() = start;
        if (i > 0)
        {
            evaluateCoupledPatches(f);
        }
        else
        {
            f.correctBoundaryConditions();
        }
    }
    result.applied = true;
    return result;
}

// ************************************************************************* //
