// SPDX-License-Identifier: GPL-3.0-or-later
// MPMD world redirect (target fsi_comm_world_redirect), linked into the fluid executable.
//
// Defines exactly the MPI_* functions that OpenFOAM v1912's libPstream.so imports
// (`nm -D --undefined-only /usr/lib/libPstream.so`). While the redirect is on, a
// communicator argument equal to MPI_COMM_WORLD is replaced by the fluid program's own
// communicator; every call then goes to the PMPI_* entry point. Off (the default), all calls
// pass through unchanged.
// Not redirected on purpose: MPI_Abort (a fatal error must stop the whole MPMD job) and
// MPI_Comm_free (MPI_COMM_WORLD must never be freed, and freeing it must not free ours).
// MPI_Init_thread accepts an MPI that is already running (we initialise before OpenFOAM);
// MPI_Finalize finalises once, later calls succeed without effect.
#include "fsi/comm/MpmdWorld.hpp"

#include <dlfcn.h>
#include <stdexcept>

namespace
{
MPI_Comm redirectTarget = MPI_COMM_NULL;

inline MPI_Comm world(MPI_Comm comm)
{
    return (comm == MPI_COMM_WORLD && redirectTarget != MPI_COMM_NULL) ? redirectTarget : comm;
}
} // namespace

extern "C"
{
    int MPI_Init_thread(int* argc, char*** argv, int required, int* provided)
    {
        int initialised = 0;
        PMPI_Initialized(&initialised);
        if (initialised)
            return PMPI_Query_thread(provided);
        return PMPI_Init_thread(argc, argv, required, provided);
    }

    int MPI_Initialized(int* flag)
    {
        return PMPI_Initialized(flag);
    }

    int MPI_Finalized(int* flag)
    {
        return PMPI_Finalized(flag);
    }

    int MPI_Finalize(void)
    {
        int finalised = 0;
        PMPI_Finalized(&finalised);
        if (finalised)
            return MPI_SUCCESS;
        redirectTarget = MPI_COMM_NULL;
        return PMPI_Finalize();
    }

    int MPI_Comm_size(MPI_Comm comm, int* size)
    {
        return PMPI_Comm_size(world(comm), size);
    }

    int MPI_Comm_rank(MPI_Comm comm, int* rank)
    {
        return PMPI_Comm_rank(world(comm), rank);
    }

    int MPI_Comm_group(MPI_Comm comm, MPI_Group* group)
    {
        return PMPI_Comm_group(world(comm), group);
    }

    int MPI_Comm_create(MPI_Comm comm, MPI_Group group, MPI_Comm* newcomm)
    {
        return PMPI_Comm_create(world(comm), group, newcomm);
    }

    int MPI_Allreduce(const void* sendbuf, void* recvbuf, int count, MPI_Datatype datatype,
                      MPI_Op op, MPI_Comm comm)
    {
        return PMPI_Allreduce(sendbuf, recvbuf, count, datatype, op, world(comm));
    }

    int MPI_Alltoall(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf,
                     int recvcount, MPI_Datatype recvtype, MPI_Comm comm)
    {
        return PMPI_Alltoall(sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype,
                             world(comm));
    }

    int MPI_Alltoallv(const void* sendbuf, const int sendcounts[], const int sdispls[],
                      MPI_Datatype sendtype, void* recvbuf, const int recvcounts[],
                      const int rdispls[], MPI_Datatype recvtype, MPI_Comm comm)
    {
        return PMPI_Alltoallv(sendbuf, sendcounts, sdispls, sendtype, recvbuf, recvcounts, rdispls,
                              recvtype, world(comm));
    }

    int MPI_Gatherv(const void* sendbuf, int sendcount, MPI_Datatype sendtype, void* recvbuf,
                    const int recvcounts[], const int displs[], MPI_Datatype recvtype, int root,
                    MPI_Comm comm)
    {
        return PMPI_Gatherv(sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype,
                            root, world(comm));
    }

    int MPI_Scatterv(const void* sendbuf, const int sendcounts[], const int displs[],
                     MPI_Datatype sendtype, void* recvbuf, int recvcount, MPI_Datatype recvtype,
                     int root, MPI_Comm comm)
    {
        return PMPI_Scatterv(sendbuf, sendcounts, displs, sendtype, recvbuf, recvcount, recvtype,
                             root, world(comm));
    }

    int MPI_Send(const void* buf, int count, MPI_Datatype datatype, int dest, int tag,
                 MPI_Comm comm)
    {
        return PMPI_Send(buf, count, datatype, dest, tag, world(comm));
    }

    int MPI_Bsend(const void* buf, int count, MPI_Datatype datatype, int dest, int tag,
                  MPI_Comm comm)
    {
        return PMPI_Bsend(buf, count, datatype, dest, tag, world(comm));
    }

    int MPI_Isend(const void* buf, int count, MPI_Datatype datatype, int dest, int tag,
                  MPI_Comm comm, MPI_Request* request)
    {
        return PMPI_Isend(buf, count, datatype, dest, tag, world(comm), request);
    }

    int MPI_Recv(void* buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm,
                 MPI_Status* status)
    {
        return PMPI_Recv(buf, count, datatype, source, tag, world(comm), status);
    }

    int MPI_Irecv(void* buf, int count, MPI_Datatype datatype, int source, int tag, MPI_Comm comm,
                  MPI_Request* request)
    {
        return PMPI_Irecv(buf, count, datatype, source, tag, world(comm), request);
    }

    int MPI_Probe(int source, int tag, MPI_Comm comm, MPI_Status* status)
    {
        return PMPI_Probe(source, tag, world(comm), status);
    }
} // extern "C"

namespace fsi::comm
{

MPI_Comm worldRedirectTarget()
{
    return redirectTarget;
}

LaunchOptions initialiseMpmdWorld(int& argc, char**& argv)
{
    LaunchOptions options = parseLaunchOptions(argc, argv);
    // libPstream.so only sees our definitions if the executable exports them.
    if (dlsym(RTLD_DEFAULT, "MPI_Comm_size") != reinterpret_cast<void*>(&MPI_Comm_size))
    {
        throw std::runtime_error(
            "fsi::comm: the MPMD world redirect is not exported from this executable; link "
            "fsi_comm_world_redirect into the executable itself (see comm/README.md)");
    }
    initialiseMpi(argc, argv);
    if (options.mode == LaunchMode::Mpmd && redirectTarget == MPI_COMM_NULL)
    {
        const MpmdLayout& layout = mpmdLayout(options.timeoutSeconds);
        MPI_Comm own = MPI_COMM_NULL;
        if (PMPI_Comm_dup(layout.programComm, &own) != MPI_SUCCESS)
            throw std::runtime_error("fsi::comm: MPI_Comm_dup of the fluid communicator failed");
        redirectTarget = own;
    }
    return options;
}

} // namespace fsi::comm
