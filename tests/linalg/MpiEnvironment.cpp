// SPDX-License-Identifier: GPL-3.0-or-later
// MPI_Init/Finalize around all tests (works with gtest_main); only rank 0 prints.
#include <gtest/gtest.h>
#include <mpi.h>

namespace
{
class MpiEnvironment : public ::testing::Environment
{
public:
    void SetUp() override
    {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (!initialised)
            MPI_Init(nullptr, nullptr);
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        if (rank != 0)
            delete ::testing::UnitTest::GetInstance()->listeners().Release(
                ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
    }
    void TearDown() override { MPI_Finalize(); }
};

[[maybe_unused]] ::testing::Environment* const environment =
    ::testing::AddGlobalTestEnvironment(new MpiEnvironment);
} // namespace
