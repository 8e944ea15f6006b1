// SPDX-License-Identifier: GPL-3.0-or-later
// rbf-pu specifics: exactness where patches are degenerate or targets lie off the interface,
// accuracy against rbf-wendland-c2, tiny interfaces, parameter and input errors.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using namespace fsi::mapping;
using namespace fsi::mapping::test;

namespace
{

MappingParameters partitionOfUnity()
{
    MappingParameters p;
    p.strategy = mappingType("rbf-pu").defaults();
    return p;
}

Values smoothField(const PointCloud& x)
{
    Values f(x.rows(), 1);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        f(i, 0) = std::sin(3.0 * x(i, 0)) * std::cos(2.0 * x(i, 1)) + std::sin(4.0 * x(i, 2));
    return f;
}

// Relative errors of total force and total moment after mapping forces g on t to s.
std::pair<double, double> conservationErrors(const Mapping& mapping, const PointCloud& s,
                                             const PointCloud& t)
{
    const Values g = faceForces(t.rows());
    Values f(s.rows(), 3);
    mapping.applyConservative(g, f);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    const double momentScale = forceScale * Values(t).rowwise().norm().maxCoeff();
    return {(f.colwise().sum() - g.colwise().sum()).norm() / forceScale,
            (totalMoment(s, f) - totalMoment(t, g)).norm() / momentScale};
}

} // namespace

TEST(PartitionOfUnity, CoplanarPatchesKeepLinearFieldsExactOffThePlane)
{
    // Targets 2 mm off the planes: a coplanar patch alone cannot tell how a field varies
    // across its plane; the global linear correction restores exactness.
    const PointCloud s = corner(30, 0.0, 0.0), t = corner(41, 0.3, 0.002);
    const auto mapping = buildMapping(partitionOfUnity(), s, t);
    const auto& pu = dynamic_cast<const RbfPartitionOfUnity&>(*mapping);
    std::printf("corner: %ld -> %ld points, %ld patches, %ld coplanar, %ld corrected targets\n",
                long(s.rows()), long(t.rows()), long(pu.patchCount()), long(pu.degeneratePatches()),
                long(pu.correctedTargets()));
    EXPECT_GT(pu.degeneratePatches(), 0);
    EXPECT_GT(pu.correctedTargets(), 0);
    Values mapped(t.rows(), 3);
    mapping->applyConsistent(linearField(s), mapped);
    EXPECT_LT(relativeMaxError(mapped, linearField(t)), 1e-10);
    mapping->applyConsistent(Values::Constant(s.rows(), 1, 2.5), mapped.leftCols(1));
    EXPECT_LT((mapped.col(0).array() - 2.5).abs().maxCoeff(), 1e-12);
    const auto [force, moment] = conservationErrors(*mapping, s, t);
    EXPECT_LT(force, 1e-12);
    EXPECT_LT(moment, 1e-12);
}

TEST(PartitionOfUnity, TargetsAwayFromTheInterfaceStayExact)
{
    // A few targets 5 % of the interface size off the cylinder: no patch of their neighbours
    // reaches them, so each becomes the centre of a patch (extrapolating its nearest sources);
    // linear fields stay exact and forces conserved.
    const PointCloud s = solidCylinder(24);
    PointCloud t = fluidCylinder(24);
    for (Eigen::Index i = 0; i < t.rows(); i += 97)
        t(i, 0) += 0.07;
    const auto mapping = buildMapping(partitionOfUnity(), s, t);
    Values mapped(t.rows(), 3);
    mapping->applyConsistent(linearField(s), mapped);
    EXPECT_LT(relativeMaxError(mapped, linearField(t)), 1e-10);
    const auto [force, moment] = conservationErrors(*mapping, s, t);
    EXPECT_LT(force, 1e-12);
    EXPECT_LT(moment, 1e-12);
}

TEST(PartitionOfUnity, UnstructuredCloudsStayExact)
{
    // Random points on a sphere of radius 0.3 m (no grid structure: irregular, sometimes
    // nearly collinear patches), targets 1 mm off the surface; and a random volume cloud.
    std::mt19937 random(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto sphere = [&](Eigen::Index n, double radius)
    {
        PointCloud p(n, 3);
        for (Eigen::Index i = 0; i < n; ++i)
        {
            const Eigen::RowVector3d d(normal(random), normal(random), normal(random));
            p.row(i) = Eigen::RowVector3d(0.1, 0.2, -0.3) + radius * d.normalized();
        }
        return p;
    };
    PointCloud volume(1500, 3);
    for (Eigen::Index i = 0; i < volume.rows(); ++i)
        volume.row(i) << normal(random), normal(random), 0.3 * normal(random);
    const PointCloud volumeTargets = 0.9 * volume.topRows(700);
    for (const auto& [s, t] :
         {std::pair{sphere(2000, 0.3), sphere(3000, 0.301)}, std::pair{volume, volumeTargets}})
    {
        const auto mapping = buildMapping(partitionOfUnity(), s, t);
        Values mapped(t.rows(), 3);
        mapping->applyConsistent(linearField(s), mapped);
        EXPECT_LT(relativeMaxError(mapped, linearField(t)), 1e-10);
        const auto [force, moment] = conservationErrors(*mapping, s, t);
        EXPECT_LT(force, 1e-12);
        EXPECT_LT(moment, 1e-12);
    }
}

TEST(PartitionOfUnity, AsAccurateAsWendlandOnASmoothField)
{
    // Same clouds as the convergence study (nTheta = 48, 1200 source points), Wendland C2 with
    // its fixed support radius 0.5 m (its convergence test) and with 4 solid spacings (what
    // the bench uses). Observed: rbf-pu 6.8e-4, Wendland 4.0e-3 (0.5 m) and 1.3e-2 (4 h).
    const PointCloud s = solidCylinder(48), t = fluidCylinder(48);
    const Values exact = smoothField(t);
    Values mapped(t.rows(), 1);
    const auto error = [&](const MappingParameters& p)
    {
        buildMapping(p, s, t)->applyConsistent(smoothField(s), mapped);
        return relativeMaxError(mapped, exact);
    };
    const double pu = error(partitionOfUnity());
    MappingParameters wendland;
    wendland.strategy = mappingType("rbf-wendland-c2").defaults();
    wendland.strategy.get<WendlandParameters>()->supportRadius = 0.5;
    const double wendlandWide = error(wendland);
    wendland.strategy.get<WendlandParameters>()->supportRadius = 4.0 * std::acos(-1.0) / 48.0;
    const double wendlandNarrow = error(wendland);
    std::printf("max relative error: rbf-pu %.2e, rbf-wendland-c2 0.5 m %.2e, 4 h %.2e\n", pu,
                wendlandWide, wendlandNarrow);
    EXPECT_LT(pu, 1.5e-3);
    EXPECT_LE(pu, wendlandWide);
    EXPECT_LE(pu, wendlandNarrow);
}

TEST(PartitionOfUnity, TinyInterfacesReproduceConstants)
{
    // Fewer source points than points_per_patch: one patch of all of them.
    for (const int n : {1, 2, 3, 7})
    {
        PointCloud s(n, 3), t(5, 3);
        for (int i = 0; i < n; ++i)
            s.row(i) << 0.1 * i, 0.05 * i * i, 0.0;
        for (int i = 0; i < 5; ++i)
            t.row(i) << 0.02 * i, 0.01, 0.001 * i;
        const auto mapping = makeMapping(partitionOfUnity()); // (no overlap check: one point)
        mapping->compute(s, t);
        Values mapped(5, 1);
        mapping->applyConsistent(Values::Constant(n, 1, -3.0), mapped);
        EXPECT_LT((mapped.array() + 3.0).abs().maxCoeff(), 1e-12) << n << " source points";
        Values back(n, 1);
        mapping->applyConservative(Values::Ones(5, 1), back);
        EXPECT_NEAR(back.sum(), 5.0, 1e-12) << n << " source points";
    }
}

TEST(PartitionOfUnity, RejectsBadInputWithOneLineMessages)
{
    const auto message = [](const MappingParameters& p)
    {
        try
        {
            p.validate();
        }
        catch (const std::runtime_error& e)
        {
            return std::string(e.what());
        }
        return std::string();
    };
    MappingParameters p = partitionOfUnity();
    EXPECT_EQ(message(p), "");
    p.strategy.get<PartitionOfUnityParameters>()->pointsPerPatch = 3;
    EXPECT_EQ(message(p), "mapping.rbf-pu.points_per_patch must be in [4, 200] (got 3); e.g. 20");
    p = partitionOfUnity();
    p.strategy.get<PartitionOfUnityParameters>()->centreSpacing = 1.0;
    EXPECT_EQ(message(p), "mapping.rbf-pu.centre_spacing must be in (0, 1) (got 1); e.g. 0.85");
    p.strategy.get<PartitionOfUnityParameters>()->centreSpacing = std::nan("");
    EXPECT_NE(message(p).find("mapping.rbf-pu.centre_spacing"), std::string::npos);
    for (const std::string& text : {message(p), message(partitionOfUnity())})
        EXPECT_EQ(text.find('\n'), std::string::npos);

    // Coinciding source points are named, and so is the fix.
    PointCloud s = solidCylinder(16);
    s.row(40) = s.row(41);
    try
    {
        buildMapping(partitionOfUnity(), s, fluidCylinder(16));
        FAIL() << "expected an error";
    }
    catch (const std::runtime_error& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("mapping rbf-pu: source points"), std::string::npos) << what;
        EXPECT_NE(what.find("coincide"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    EXPECT_THROW(makeMapping(partitionOfUnity())->compute(PointCloud(0, 3), s), std::runtime_error);
}
