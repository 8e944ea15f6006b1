// SPDX-License-Identifier: GPL-3.0-or-later
// Initialises MPI once for a GoogleTest binary (gtest_main provides main()).
#pragma once
#include <gtest/gtest.h>
#include <mpi.h>

namespace fsi::testing
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
    }
    void TearDown() override
    {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised)
            MPI_Finalize();
    }
};
inline ::testing::Environment* const mpiEnvironment =
    ::testing::AddGlobalTestEnvironment(new MpiEnvironment);
} // namespace fsi::testing
