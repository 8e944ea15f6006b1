// SPDX-License-Identifier: GPL-3.0-or-later
// Set-up checks: quality figures on a case where they are known; non-overlapping interfaces.
#include "Clouds.hpp"

#include "mapping/Quality.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace fsi::mapping;
using fsi::mapping::test::plate;
using fsi::mapping::test::solidCylinder;

namespace
{
std::string errorOf(const PointCloud& s, const PointCloud& t, double tolerance)
{
    try
    {
        checkOverlap(s, t, tolerance);
    }
    catch (const std::runtime_error& e)
    {
        return e.what();
    }
    return "";
}
} // namespace

TEST(MappingQuality, KnownFiguresForAShiftedGrid)
{
    // Source: 11 x 11 grid on [0,1]^2 (spacing 0.1 m) at z = 0.2; target: the same grid shifted
    // by 0.03 m in x. Nearest distance 0.03 m everywhere; interface size sqrt(2) m; overlap
    // (x: 0.97/1.03, y: 1, z flat and skipped); nearest-neighbour moves each coordinate by 0.03 m,
    // the RBF mappings reproduce coordinates (linear) exactly.
    const PointCloud s = plate(11, 11, 1.0, 1.0, 0.0, 0.0), t = plate(11, 11, 1.0, 1.0, 0.03, 0.0);
    MappingParameters p;
    const auto nn = buildMapping(p, s, t);
    const MappingQuality q = assessQuality(*nn, s, t);
    EXPECT_NEAR(q.interfaceSize, std::sqrt(2.0), 1e-14);
    EXPECT_NEAR(q.maxNearestDistance, 0.03, 1e-14);
    EXPECT_NEAR(q.boundingBoxOverlap, 0.97 / 1.03, 1e-14);
    EXPECT_NEAR(q.coordinateRmsError, 0.03, 1e-14);
    EXPECT_NEAR(q.coordinateMaxError, 0.03, 1e-14);
    std::printf("nearest-neighbour: %s\n", q.toString().c_str());
    EXPECT_NE(q.toString().find("max nearest distance 3.000e-02 m"), std::string::npos);

    for (const char* type : {"rbf-thin-plate", "rbf-wendland-c2"})
    {
        p.strategy = mappingType(type).defaults();
        if (auto* w = p.strategy.get<WendlandParameters>())
            w->supportRadius = 0.35;
        const MappingQuality r = assessQuality(*buildMapping(p, s, t), s, t);
        std::printf("%s: %s\n", type, r.toString().c_str());
        EXPECT_LT(r.coordinateMaxError, 1e-12) << type;
        EXPECT_NEAR(r.maxNearestDistance, 0.03, 1e-14);
    }
}

TEST(MappingQuality, GeometryOnlyLeavesCoordinateErrorsUnset)
{
    const PointCloud s = solidCylinder(16);
    const MappingQuality q = assessGeometry(s, s);
    EXPECT_EQ(q.maxNearestDistance, 0.0);
    EXPECT_NEAR(q.boundingBoxOverlap, 1.0, 1e-15);
    EXPECT_TRUE(std::isnan(q.coordinateRmsError));
}

TEST(MappingOverlap, RefusesDisjointBoundingBoxes)
{
    // The fluid mesh given in mm against a solid mesh in m: the boxes do not meet.
    const PointCloud s = plate(11, 11, 1.0, 1.0, 0.0, 0.0);
    const PointCloud t = plate(11, 11, 1000.0, 1000.0, 10.0, 10.0);
    const std::string message = errorOf(s, t, 0.1);
    EXPECT_EQ(message.rfind("mapping: interfaces do not overlap: bounding boxes are disjoint "
                            "(solid [0 0 0.2]..[1 1 0.2] m, fluid [10 10 0.2]..[1010 1010 0.2] m)",
                            0),
              0u)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
    MappingParameters p;
    EXPECT_THROW(buildMapping(p, s, t), std::runtime_error);
}

TEST(MappingOverlap, RefusesTargetsFarFromEverySource)
{
    // Boxes overlap but one target sits 0.5 m above the plate (interface size sqrt(2) m).
    const PointCloud s = plate(11, 11, 1.0, 1.0, 0.0, 0.0);
    PointCloud t = plate(6, 6, 1.0, 1.0, 0.0, 0.0);
    t(7, 2) = 0.7;
    EXPECT_EQ(errorOf(s, t, 0.1),
              "mapping: interfaces do not overlap: target point (0.2 0.2 0.7) m is 5.000e-01 m "
              "from the nearest source point, above mapping.overlap_tolerance 0.1 x interface "
              "size 1.414e+00 m; check units and placement of both meshes or raise "
              "mapping.overlap_tolerance");
    EXPECT_EQ(errorOf(s, t, 0.5), ""); // 0.5 m < 0.5 x 1.414 m
}
