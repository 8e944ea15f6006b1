// SPDX-License-Identifier: GPL-3.0-or-later
// MPI_Init/Finalize around all tests (works with gtest_main); rank 0 prints the usual
// report, the other ranks only their failures.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>

namespace
{
// On ranks other than 0: print failures only, prefixed with the rank.
class FailurePrinter : public ::testing::EmptyTestEventListener
{
public:
    explicit FailurePrinter(int rank) : rank_(rank) {}
    void OnTestPartResult(const ::testing::TestPartResult& result) override
    {
        if (result.failed())
            std::fprintf(stderr, "[rank %d] %s:%d: %s\n", rank_,
                         result.file_name() ? result.file_name() : "?", result.line_number(),
                         result.summary());
    }

private:
    int rank_;
};

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
        {
            auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
            delete listeners.Release(listeners.default_result_printer());
            listeners.Append(new FailurePrinter(rank));
        }
    }
    void TearDown() override { MPI_Finalize(); }
};

[[maybe_unused]] ::testing::Environment* const environment =
    ::testing::AddGlobalTestEnvironment(new MpiEnvironment);
} // namespace
