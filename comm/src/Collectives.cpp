// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/Collectives.hpp"

#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <numeric>
#include <sstream>
#include <thread>

namespace fsi::comm
{

void checkMpi(int code, const std::string& what)
{
    if (code == MPI_SUCCESS)
        return;
    char text[MPI_MAX_ERROR_STRING] = {};
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw CommError("fsi::comm: " + what + " failed: " + std::string(text, length));
}

bool pollUntil(const std::function<bool()>& done, double timeoutSeconds)
{
    using Clock = std::chrono::steady_clock;
    // Saturate: a clock count of nanoseconds overflows near 9.2e9 s.
    const double bounded = std::min(timeoutSeconds, kMaxTimeoutSeconds);
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(bounded));
    // Spin briefly (latency of a coupling exchange), then sleep with a growing pause (<= 2 ms).
    auto pause = std::chrono::microseconds(20);
    for (long polls = 0;; ++polls)
    {
        if (done())
            return true;
        if (Clock::now() >= deadline)
            return false;
        if (polls > 200)
        {
            std::this_thread::sleep_for(pause);
            pause = std::min(pause * 2, std::chrono::microseconds(2000));
        }
    }
}

void waitBounded(MPI_Request& request, double timeoutSeconds, const std::string& what,
                 MPI_Status* status)
{
    const bool completed = pollUntil(
        [&]
        {
            int flag = 0;
            checkMpi(MPI_Test(&request, &flag, status), what);
            return flag != 0;
        },
        timeoutSeconds);
    if (!completed)
    {
        std::ostringstream text;
        text << "fsi::comm: " << what << " did not complete within " << timeoutSeconds << " s";
        throw TimeoutError(text.str());
    }
}

namespace
{
int toInt(std::int64_t n, const char* what)
{
    if (n < 0 || n > INT_MAX)
        throw CommError(std::string("fsi::comm: ") + what +
                        " count out of range: " + std::to_string(n));
    return static_cast<int>(n);
}
} // namespace

std::vector<double> gatherToRoot(MPI_Comm comm, const std::vector<double>& local,
                                 double timeoutSeconds)
{
    int rank = 0, size = 1;
    checkMpi(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
    checkMpi(MPI_Comm_size(comm, &size), "MPI_Comm_size");
    int mine = toInt(static_cast<std::int64_t>(local.size()), "gatherToRoot");
    std::vector<int> counts(rank == 0 ? size : 0), offsets(rank == 0 ? size : 0);
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Igather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm, &request),
             "gatherToRoot (sizes)");
    waitBounded(request, timeoutSeconds, "gatherToRoot (sizes) on the local ranks");
    std::vector<double> all;
    if (rank == 0)
    {
        std::int64_t total = 0;
        for (int r = 0; r < size; ++r)
        {
            offsets[r] = toInt(total, "gatherToRoot");
            total += counts[r];
        }
        all.resize(static_cast<std::size_t>(toInt(total, "gatherToRoot")));
    }
    checkMpi(MPI_Igatherv(local.data(), mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                          MPI_DOUBLE, 0, comm, &request),
             "gatherToRoot");
    waitBounded(request, timeoutSeconds, "gatherToRoot on the local ranks");
    return all;
}

std::vector<double> scatterFromRoot(MPI_Comm comm, const std::vector<double>& rootValues,
                                    std::int64_t localCount, double timeoutSeconds)
{
    int rank = 0, size = 1;
    checkMpi(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
    checkMpi(MPI_Comm_size(comm, &size), "MPI_Comm_size");
    int mine = toInt(localCount, "scatterFromRoot");
    std::vector<int> counts(rank == 0 ? size : 0), offsets(rank == 0 ? size : 0);
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Igather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm, &request),
             "scatterFromRoot (sizes)");
    waitBounded(request, timeoutSeconds, "scatterFromRoot (sizes) on the local ranks");
    // The root checks the sizes and tells everybody, so all ranks fail together.
    std::int64_t status[2] = {0, static_cast<std::int64_t>(rootValues.size())};
    if (rank == 0)
    {
        std::int64_t total = 0;
        for (int r = 0; r < size; ++r)
        {
            offsets[r] = toInt(total, "scatterFromRoot");
            total += counts[r];
        }
        status[0] = total;
    }
    checkMpi(MPI_Ibcast(status, 2, MPI_INT64_T, 0, comm, &request), "scatterFromRoot (check)");
    waitBounded(request, timeoutSeconds, "scatterFromRoot (check) on the local ranks");
    if (status[0] != status[1])
    {
        throw CommError("fsi::comm: scatterFromRoot: the ranks own " + std::to_string(status[0]) +
                        " values in total but the root passed " + std::to_string(status[1]));
    }
    std::vector<double> mineValues(static_cast<std::size_t>(mine));
    checkMpi(MPI_Iscatterv(rootValues.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                           mineValues.data(), mine, MPI_DOUBLE, 0, comm, &request),
             "scatterFromRoot");
    waitBounded(request, timeoutSeconds, "scatterFromRoot on the local ranks");
    return mineValues;
}

void broadcastFromRoot(MPI_Comm comm, std::vector<double>& values, double timeoutSeconds)
{
    std::int64_t count = static_cast<std::int64_t>(values.size());
    MPI_Request request = MPI_REQUEST_NULL;
    checkMpi(MPI_Ibcast(&count, 1, MPI_INT64_T, 0, comm, &request), "broadcastFromRoot (size)");
    waitBounded(request, timeoutSeconds, "broadcastFromRoot (size) on the local ranks");
    values.resize(static_cast<std::size_t>(toInt(count, "broadcastFromRoot")));
    checkMpi(MPI_Ibcast(values.data(), static_cast<int>(count), MPI_DOUBLE, 0, comm, &request),
             "broadcastFromRoot");
    waitBounded(request, timeoutSeconds, "broadcastFromRoot on the local ranks");
}

} // namespace fsi::comm
