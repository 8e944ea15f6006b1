// SPDX-License-Identifier: GPL-3.0-or-later
// Interface arrays distributed over the ranks of one program: bounded collectives on a
// local (intra)communicator. Call on every rank of comm. Root is rank 0. Arrays are in the
// caller's units; order is rank order (rank 0's part first).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fsi
{
namespace comm
{

// Root returns the concatenation of every rank's local part; other ranks return {}.
std::vector<double> gatherToRoot(MPI_Comm comm, const std::vector<double>& local,
                                 double timeoutSeconds);

// Inverse of gatherToRoot: every rank passes how many values it owns (localCount >= 0);
// the root's rootValues (size = sum of the counts, else CommError on every rank) is cut in
// rank order. Non-root rootValues are ignored.
std::vector<double> scatterFromRoot(MPI_Comm comm, const std::vector<double>& rootValues,
                                    std::int64_t localCount, double timeoutSeconds);

// After the call every rank holds the root's values (size included).
void broadcastFromRoot(MPI_Comm comm, std::vector<double>& values, double timeoutSeconds);

// Calls `done` until it returns true (returns true) or timeoutSeconds pass (returns false):
// spins for about 200 calls, then sleeps between calls with a pause doubling up to 2 ms.
// Every bounded wait on MPI progress polls through this.
bool pollUntil(const std::function<bool()>& done, double timeoutSeconds);

// Bounded wait for one request: polls MPI_Test with short sleeps until done or until
// timeoutSeconds pass; then throws TimeoutError("<what> did not complete within N s").
// MPI error codes become CommError naming what.
void waitBounded(MPI_Request& request, double timeoutSeconds, const std::string& what,
                 MPI_Status* status = MPI_STATUS_IGNORE);

// MPI return code -> CommError("<what>: <MPI error string>") unless MPI_SUCCESS.
void checkMpi(int code, const std::string& what);

} // namespace comm
} // namespace fsi
