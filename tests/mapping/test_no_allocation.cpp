// SPDX-License-Identifier: GPL-3.0-or-later
// The apply functions are on the hot path: after the first call with a given column count they
// must not allocate. This target compiles the mapping sources with EIGEN_RUNTIME_NO_MALLOC and
// assertions on, so any Eigen heap allocation while forbidden aborts the test.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fsi::mapping;
using fsi::mapping::test::corner;
using fsi::mapping::test::fluidCylinder;
using fsi::mapping::test::solidCylinder;

namespace
{
// Applies the mapping to all-ones fields once (sizing the workspace), then three times with
// Eigen's heap allocation forbidden. Returns the consistent (v) and conservative (f) results.
void applyThriceWithoutAllocation(const Mapping& mapping, Values& v, Values& f)
{
    const Values u = Values::Ones(mapping.sourceSize(), 3);
    const Values g = Values::Ones(mapping.targetSize(), 3);
    v.resize(mapping.targetSize(), 3);
    f.resize(mapping.sourceSize(), 3);
    mapping.applyConsistent(u, v); // sizes the workspace
    mapping.applyConservative(g, f);
    Eigen::internal::set_is_malloc_allowed(false);
    for (int i = 0; i < 3; ++i)
    {
        mapping.applyConsistent(u, v);
        mapping.applyConservative(g, f);
    }
    Eigen::internal::set_is_malloc_allowed(true);
}
} // namespace

TEST(MappingApply, AllocatesNothingAfterTheFirstCall)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    for (const char* type : {"nearest-neighbour", "rbf-thin-plate", "rbf-wendland-c2", "rbf-pu",
                             "moving-least-squares"})
    {
        MappingParameters p;
        p.strategy = mappingType(type).defaults();
        if (auto* w = p.strategy.get<WendlandParameters>())
        {
            w->supportRadius = 0.4;
            w->solver = "direct"; // the iterative solver allocates work vectors per solve
        }
        const auto mapping = buildMapping(p, s, t);
        Values v, f;
        applyThriceWithoutAllocation(*mapping, v, f);
        EXPECT_NEAR(v(0, 0), 1.0, 1e-12) << type;                    // constants are reproduced
        EXPECT_NEAR(f.col(0).sum(), double(t.rows()), 1e-9) << type; // total force kept
    }
}

TEST(MappingApply, PartitionOfUnityCorrectionAllocatesNothingAfterTheFirstCall)
{
    // Coplanar patches with targets off their plane: the correction path of rbf-pu.
    const PointCloud s = corner(12, 0.0, 0.0), t = corner(17, 0.3, 0.002);
    MappingParameters p;
    p.strategy = mappingType("rbf-pu").defaults();
    const auto mapping = buildMapping(p, s, t);
    Values v, f;
    applyThriceWithoutAllocation(*mapping, v, f);
    EXPECT_NEAR(v(0, 0), 1.0, 1e-12);
    EXPECT_NEAR(f.col(0).sum(), double(t.rows()), 1e-9);
}

TEST(MappingApply, NearestProjectionAllocatesNothingAfterTheFirstCall)
{
    // a flat 6 x 6 node patch of Tri3 faces; targets slightly off it
    const int m = 6;
    PointCloud s(m * m, 3);
    SourceSurface surface;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
            s.row(j * m + i) << 0.2 * i, 0.2 * j, 0.0;
    for (int j = 0; j + 1 < m; ++j)
        for (int i = 0; i + 1 < m; ++i)
        {
            const int a[3] = {j * m + i, j * m + i + 1, (j + 1) * m + i + 1};
            const int b[3] = {j * m + i, (j + 1) * m + i + 1, (j + 1) * m + i};
            surface.faces.add(fsi::mesh::CellType::Tri3, a, 3);
            surface.faces.add(fsi::mesh::CellType::Tri3, b, 3);
        }
    PointCloud t(40, 3);
    for (int k = 0; k < 40; ++k)
        t.row(k) << 0.025 * k, 0.5 + 0.3 * std::sin(0.7 * k), 0.001 * std::cos(1.3 * k);
    MappingParameters p;
    p.strategy = mappingType("nearest-projection").defaults();
    const auto mapping = buildMapping(p, s, t, &surface);
    Values v, f;
    applyThriceWithoutAllocation(*mapping, v, f);
    EXPECT_NEAR(v(0, 0), 1.0, 1e-12);            // constants are reproduced
    EXPECT_NEAR(f.sum(), 3.0 * t.rows(), 1e-10); // and the total conserved
}

TEST(MappingApply, SmoothedMappingAllocatesNothingAfterTheFirstCall)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    MappingParameters p; // nearest-neighbour, smoothed
    p.smoothingRadius = 0.15;
    const auto mapping = buildMapping(p, s, t);
    Values v, f;
    applyThriceWithoutAllocation(*mapping, v, f);
    EXPECT_NEAR(v(0, 0), 1.0, 1e-12);
    EXPECT_NEAR(f.col(0).sum(), double(t.rows()), 1e-9);
}
