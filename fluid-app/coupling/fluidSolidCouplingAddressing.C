// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the interface addressing (see fluidSolidCoupling.H): a global order of the
// interface points and faces, and the gathers to the master (geometry; the interface CSVs).
#include "fluidSolidCoupling.H"

#include "labelIOList.H"
#include "ListOps.H"

#include <algorithm>

void Foam::fluidSolidCoupling::buildGlobalOrdering()
{
    const polyPatch& pp = mesh_.boundaryMesh()[patchi_];
    const labelList& meshPoints = pp.meshPoints();

    // Global (undecomposed) labels of the local patch points and faces
    labelList pointIds(meshPoints);
    labelList faceIds(identity(pp.size(), pp.start()));
    if (Pstream::parRun())
    {
        // decomposePar's addressing of this processor's mesh (constant/polyMesh)
        const auto procAddressing = [this](const word& name)
        {
            return labelList
            (
                labelIOList
                (
                    IOobject
                    (
                        name,
                        mesh_.facesInstance(),
                        polyMesh::meshSubDir,
                        mesh_,
                        IOobject::MUST_READ,
                        IOobject::NO_WRITE,
                        false
                    )
                )
            );
        };
        const labelList pointAddr(procAddressing("pointProcAddressing"));
        const labelList faceAddr(procAddressing("faceProcAddressing"));
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

    // Every rank's faces on the master, once: it places the gathered forces of the interface
    // CSVs (the lists never change during a run).
    procFaceToGlobal_.setSize(Pstream::nProcs());
    procFaceToGlobal_[Pstream::myProcNo()] = faceToGlobal_;
    Pstream::gatherList(procFaceToGlobal_);
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
    const List<labelList>& fIds = procFaceToGlobal_; // on the master
    List<vectorField> f(nProcs);
    f[me] = localForces;
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

// ************************************************************************* //
