// SPDX-License-Identifier: GPL-3.0-or-later
// CsrPattern from element dofs; METIS element partition of structured tet and hex meshes.
#include "linalg/CsrPattern.hpp"
#include "linalg/Partition.hpp"
#include "CubeMesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace fsi::linalg;

namespace
{
using fsi::testing::cubeElements;
} // namespace

TEST(CsrPattern, TwoElementsSharingDofs)
{
    const CsrPattern full = CsrPattern::fromElements(5, {{0, 1, 2}, {2, 3, 4}});
    EXPECT_EQ(full.size(), 5);
    EXPECT_EQ(full.nonZeros(), 9u + 9u - 1u);
    EXPECT_GE(full.find(2, 4), 0);
    EXPECT_GE(full.find(0, 2), 0);
    EXPECT_EQ(full.find(0, 3), -1);
    EXPECT_EQ(full.find(7, 0), -1);
    const auto rows = full.tripletRows();
    const auto& cols = full.columns();
    for (std::size_t k = 0; k < rows.size(); ++k)
        EXPECT_EQ(full.find(rows[k], cols[k]), static_cast<long>(k));
    for (int r = 0; r < 5; ++r)
        EXPECT_TRUE(std::is_sorted(cols.begin() + full.rowOffsets()[r],
                                   cols.begin() + full.rowOffsets()[r + 1]));

    const CsrPattern lower = CsrPattern::fromElements(5, {{0, 1, 2}, {2, -1, 3, 4}}, true);
    EXPECT_EQ(lower.nonZeros(), 6u + 6u - 1u); // constrained dof -1 skipped
    EXPECT_EQ(lower.find(0, 2), -1);
    EXPECT_GE(lower.find(2, 0), 0);
}

class PartitionMesh : public ::testing::TestWithParam<std::tuple<bool, int>>
{
};

TEST_P(PartitionMesh, CoversEveryElementOnceAndIsBalanced)
{
    const auto [tets, parts] = GetParam();
    const auto elements = cubeElements(10, tets);
    const int ne = static_cast<int>(elements.size());
    const std::vector<int> part = partitionElements(elements, parts, tets ? 3 : 4);
    ASSERT_EQ(static_cast<int>(part.size()), ne); // one part id per element: exactly once
    std::vector<int> count(parts, 0);
    for (int p : part)
    {
        ASSERT_GE(p, 0);
        ASSERT_LT(p, parts);
        ++count[p];
    }
    const int largest = *std::max_element(count.begin(), count.end());
    const int smallest = *std::min_element(count.begin(), count.end());
    EXPECT_GT(smallest, 0);
    EXPECT_LE(largest, 1.05 * ne / parts) << "imbalance " << largest * parts / double(ne);
    // deterministic
    EXPECT_EQ(part, partitionElements(elements, parts, tets ? 3 : 4));
}

INSTANTIATE_TEST_SUITE_P(Meshes, PartitionMesh,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(1, 2, 3, 4, 7)));

TEST(Partition, TinyAndInvalidInput)
{
    EXPECT_EQ(partitionElements({{0, 1, 2, 3}, {1, 2, 3, 4}}, 4), (std::vector<int>{0, 1}));
    EXPECT_THROW(partitionElements({{0, 1, 2, 3}}, 0), std::invalid_argument);
    EXPECT_THROW(partitionElements(2, {0, 4}, {0, 1, 2, 3}, 2), std::invalid_argument);
}
