// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/MpmdWorld.hpp"

#include "Watchdog.hpp"
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/Errors.hpp"

#include <memory>
#include <set>

// Calls on MPI_COMM_WORLD use PMPI_* so that they reach the real world even in an executable
// whose MPI_* are redirected (fsi_comm_world_redirect).

namespace fsi::comm
{

void initialiseMpi(int& argc, char**& argv)
{
    int initialised = 0;
    PMPI_Initialized(&initialised);
    if (initialised)
        return;
    int provided = 0;
    checkMpi(PMPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
}

void finaliseMpi()
{
    int initialised = 0, finalised = 0;
    PMPI_Initialized(&initialised);
    PMPI_Finalized(&finalised);
    if (initialised && !finalised)
        PMPI_Finalize();
}

const MpmdLayout& mpmdLayout(double timeoutSeconds)
{
    static std::unique_ptr<MpmdLayout> layout;
    if (layout)
        return *layout;
    int initialised = 0;
    PMPI_Initialized(&initialised);
    if (!initialised)
        throw CommError("fsi::comm: MPI is not initialised; call fsi::comm::initialiseMpi first");

    auto result = std::make_unique<MpmdLayout>();
    PMPI_Comm_rank(MPI_COMM_WORLD, &result->worldRank);
    PMPI_Comm_size(MPI_COMM_WORLD, &result->worldSize);
    int* appNumber = nullptr;
    int flag = 0;
    PMPI_Comm_get_attr(MPI_COMM_WORLD, MPI_APPNUM, &appNumber, &flag);
    result->appNumber = flag ? *appNumber : 0;

    std::vector<int> appOfRank(static_cast<std::size_t>(result->worldSize));
    {
        // All processes of the launch must get here; bound the wait for the other program.
        detail::Watchdog guard(timeoutSeconds,
                               result->worldRank == 0
                                   ? "fsi::comm: MPMD start-up (split of MPI_COMM_WORLD) did not "
                                     "complete within " +
                                         std::to_string(static_cast<long>(timeoutSeconds)) +
                                         " s: the other program did not start its coupling "
                                         "(crashed, or not an fsi program?)"
                                   : std::string(),
                               kExitCommTimeout);
        checkMpi(PMPI_Allgather(&result->appNumber, 1, MPI_INT, appOfRank.data(), 1, MPI_INT,
                                MPI_COMM_WORLD),
                 "MPMD layout (MPI_Allgather on MPI_COMM_WORLD)");
        checkMpi(PMPI_Comm_split(MPI_COMM_WORLD, result->appNumber, result->worldRank,
                                 &result->programComm),
                 "MPMD split (MPI_Comm_split of MPI_COMM_WORLD)");
    }
    std::set<int> apps(appOfRank.begin(), appOfRank.end());
    result->appCount = static_cast<int>(apps.size());
    if (result->appCount != 2 || *apps.begin() != 0 || *apps.rbegin() != 1)
    {
        throw CommError("fsi::comm: --launch mpmd needs exactly two programs on one mpirun line "
                        "(mpirun -np A fluid-app ... : -np B solid-app ...); found " +
                        std::to_string(result->appCount));
    }
    result->appLeaders.assign(2, -1);
    for (int r = result->worldSize - 1; r >= 0; --r)
        result->appLeaders[static_cast<std::size_t>(appOfRank[static_cast<std::size_t>(r)])] = r;
    layout = std::move(result);
    return *layout;
}

} // namespace fsi::comm
