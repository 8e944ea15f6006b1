// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/MpmdWorld.hpp"

#include "Watchdog.hpp"
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/Errors.hpp"

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <set>
#include <sstream>

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

LaunchShape launchShape()
{
    LaunchShape shape;
    int initialised = 0;
    PMPI_Initialized(&initialised);
    if (!initialised)
        return shape;
    PMPI_Comm_rank(MPI_COMM_WORLD, &shape.worldRank);
    int* appNumber = nullptr;
    int flag = 0;
    PMPI_Comm_get_attr(MPI_COMM_WORLD, MPI_APPNUM, &appNumber, &flag);
    shape.appNumber = flag && appNumber ? *appNumber : 0;
    if (const char* count = std::getenv("OMPI_NUM_APP_CTX"))
        shape.programs = std::max(1, std::atoi(count));
    if (shape.appNumber > 0)
        shape.programs = std::max(shape.programs, shape.appNumber + 1);
    // Programs occupy consecutive world ranks in launch order: sum the earlier ones' sizes.
    shape.firstWorldRank = shape.appNumber == 0 ? 0 : shape.worldRank;
    if (const char* sizes = std::getenv("OMPI_APP_CTX_NUM_PROCS"))
    {
        std::istringstream in(sizes);
        int first = 0, size = 0;
        for (int app = 0; app < shape.appNumber && in >> size; ++app)
            first += size;
        if (in)
            shape.firstWorldRank = first;
    }
    return shape;
}

bool multiProgramLaunch()
{
    return launchShape().programs > 1;
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
        // Each program's first process prints (world rank 0 alone left the second one silent).
        const LaunchShape shape = launchShape();
        std::ostringstream limit;
        limit << timeoutSeconds;
        detail::Watchdog guard(timeoutSeconds,
                               result->worldRank == shape.firstWorldRank
                                   ? "fsi::comm: MPMD start-up (split of MPI_COMM_WORLD) did not "
                                     "complete within " +
                                         limit.str() +
                                         " s: the other program did not start its coupling "
                                         "(crashed, not an fsi program, or not started with "
                                         "--launch mpmd?)"
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
