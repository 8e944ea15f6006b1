// SPDX-License-Identifier: GPL-3.0-or-later
// Stand-in for OpenFOAM's libPstream.so in the redirect test: a shared library that, like
// Pstream, calls MPI on MPI_COMM_WORLD. Its MPI_* references are resolved by the dynamic
// linker, so they reach the redirect exported by the executable.
#include <mpi.h>

#include <vector>

extern "C"
{
    int fakePstreamInitThread(int* argc, char*** argv, int* provided)
    {
        int initialised = 0;
        MPI_Initialized(&initialised);
        // OpenFOAM v1912 skips MPI_Init_thread when MPI runs; call it anyway to test that an
        // MPI initialised before is accepted.
        return MPI_Init_thread(argc, argv, MPI_THREAD_SINGLE, provided) + (initialised ? 0 : 100);
    }

    int fakePstreamWorldSize()
    {
        int size = 0;
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        return size;
    }

    int fakePstreamWorldRank()
    {
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        return rank;
    }

    int fakePstreamAllreduceSum(int value)
    {
        int sum = 0;
        MPI_Allreduce(&value, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        return sum;
    }

    // Root gathers every rank's rank number with Gatherv; returns 1 at the root if they come
    // in order 0..size-1, 1 elsewhere.
    int fakePstreamGathervRanks()
    {
        const int rank = fakePstreamWorldRank();
        const int size = fakePstreamWorldSize();
        std::vector<int> counts(size, 1), offsets(size), all(size, -1);
        for (int r = 0; r < size; ++r)
            offsets[r] = r;
        MPI_Gatherv(&rank, 1, MPI_INT, all.data(), counts.data(), offsets.data(), MPI_INT, 0,
                    MPI_COMM_WORLD);
        if (rank != 0)
            return 1;
        for (int r = 0; r < size; ++r)
            if (all[r] != r)
                return 0;
        return 1;
    }

    // Ring exchange with Isend/Recv on MPI_COMM_WORLD: returns the rank received from the left.
    int fakePstreamRing()
    {
        const int rank = fakePstreamWorldRank();
        const int size = fakePstreamWorldSize();
        int left = -1;
        MPI_Request request;
        MPI_Isend(&rank, 1, MPI_INT, (rank + 1) % size, 11, MPI_COMM_WORLD, &request);
        MPI_Recv(&left, 1, MPI_INT, (rank + size - 1) % size, 11, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        MPI_Wait(&request, MPI_STATUS_IGNORE);
        return left;
    }

    int fakePstreamFinalize()
    {
        return MPI_Finalize();
    }
}
