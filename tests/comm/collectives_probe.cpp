// SPDX-License-Identifier: GPL-3.0-or-later
// Bounded local collectives on 3 ranks (fsi_add_mpi_test, RANKS 3): exact values for gather,
// scatter and broadcast with uneven parts, a size mismatch reported on every rank, and
// waitBounded timing out while one rank is late. Prints "collectives_probe: ok" on rank 0 and
// exits 0 only if every check passed.
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/Errors.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

using namespace fsi::comm;

namespace
{
int failures = 0;
void check(bool ok, const std::string& what, int rank)
{
    if (!ok)
    {
        std::fprintf(stderr, "collectives_probe: rank %d: FAILED: %s\n", rank, what.c_str());
        ++failures;
    }
}
} // namespace

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    MPI_Comm comm;
    MPI_Comm_dup(MPI_COMM_WORLD, &comm);
    MPI_Comm_set_errhandler(comm, MPI_ERRORS_RETURN);
    int rank = 0, size = 0;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    check(size == 3, "needs 3 ranks", rank);

    // Gather: rank r owns 2r values 100 r + k (rank 0 owns none).
    std::vector<double> mine;
    for (int k = 0; k < 2 * rank; ++k)
        mine.push_back(100.0 * rank + k + 0.125);
    const std::vector<double> all = gatherToRoot(comm, mine, 10.0);
    if (rank == 0)
        check(all == std::vector<double>{100.125, 101.125, 200.125, 201.125, 202.125, 203.125},
              "gatherToRoot values", rank);
    else
        check(all.empty(), "gatherToRoot leaves non-roots empty", rank);

    // Scatter the gathered array back: each rank gets exactly its own part.
    const std::vector<double> back = scatterFromRoot(comm, all, 2 * rank, 10.0);
    check(back == mine, "scatterFromRoot returns each rank's part", rank);

    // Broadcast, including an empty array.
    std::vector<double> values =
        rank == 0 ? std::vector<double>{1.5, -2.0, 3e300} : std::vector<double>{9.0};
    broadcastFromRoot(comm, values, 10.0);
    check(values == std::vector<double>{1.5, -2.0, 3e300}, "broadcastFromRoot values", rank);
    std::vector<double> empty = rank == 0 ? std::vector<double>{} : std::vector<double>{1.0, 2.0};
    broadcastFromRoot(comm, empty, 10.0);
    check(empty.empty(), "broadcastFromRoot of an empty array", rank);

    // Root passes 5 values where the ranks own 0 + 1 + 2 = 3: every rank gets the error.
    std::string error;
    try
    {
        scatterFromRoot(comm, std::vector<double>(5, 1.0), rank, 10.0);
    }
    catch (const CommError& e)
    {
        error = e.what();
    }
    check(error == "fsi::comm: scatterFromRoot: the ranks own 3 values in total but the root "
                   "passed 5",
          "size mismatch message: '" + error + "'", rank);

    // Rank 2 is late by 3 s: waitBounded(0.5 s) must time out on ranks 0 and 1 with the
    // message, leave the request valid, and the barrier completes once rank 2 arrives.
    MPI_Request request = MPI_REQUEST_NULL;
    if (rank == 2)
        std::this_thread::sleep_for(std::chrono::milliseconds(3000));
    MPI_Ibarrier(comm, &request);
    if (rank != 2)
    {
        const auto start = std::chrono::steady_clock::now();
        std::string timeout;
        try
        {
            waitBounded(request, 0.5, "test barrier");
        }
        catch (const TimeoutError& e)
        {
            timeout = e.what();
        }
        const double waited =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        check(timeout == "fsi::comm: test barrier did not complete within 0.5 s",
              "timeout message: '" + timeout + "'", rank);
        check(waited >= 0.5 && waited < 2.5, "timed out after " + std::to_string(waited) + " s",
              rank);
        check(request != MPI_REQUEST_NULL, "request still pending after the timeout", rank);
    }
    waitBounded(request, 10.0, "test barrier, second wait");

    MPI_Comm_free(&comm);
    int total = 0;
    MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    if (rank == 0 && total == 0)
        std::printf("collectives_probe: ok\n");
    MPI_Finalize();
    return total == 0 ? 0 : 1;
}
