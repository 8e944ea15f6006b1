// SPDX-License-Identifier: GPL-3.0-or-later
// Exact properties of the mappings: linear reproduction, conservation of force and moment,
// parameter checks.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/NearestNeighbour.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfThinPlate.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <stdexcept>

using namespace fsi::mapping;
using namespace fsi::mapping::test;

namespace
{

MappingParameters params(const std::string& type)
{
    MappingParameters p;
    p.strategy = mappingType(type).defaults();
    if (auto* w = p.strategy.get<WendlandParameters>())
        w->supportRadius = 0.4; // m: about 3 solid spacings at nTheta = 24
    return p;
}

// What buildMapping throws for these inputs ("" when it succeeds).
std::string buildError(const MappingParameters& p, const PointCloud& s, const PointCloud& t)
{
    try
    {
        buildMapping(p, s, t);
    }
    catch (const std::runtime_error& e)
    {
        return e.what();
    }
    return "";
}
} // namespace

class RbfMapping : public ::testing::TestWithParam<std::string>
{
};

TEST_P(RbfMapping, ReproducesLinearFieldsOnNonMatchingCylinders)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    const auto mapping = buildMapping(params(GetParam()), s, t);
    Values mapped(t.rows(), 3);
    mapping->applyConsistent(linearField(s), mapped);
    const double error = relativeMaxError(mapped, linearField(t));
    std::printf("%s: %ld -> %ld points, linear field relative max error %.2e\n", GetParam().c_str(),
                long(s.rows()), long(t.rows()), error);
    EXPECT_LT(error, 1e-10);
}

TEST_P(RbfMapping, ReproducesLinearFieldsOnFlatInterface)
{
    // Coplanar sources: the z-direction of the polynomial is dropped, in-plane fields exact.
    const PointCloud s = plate(13, 9, 1.2, 0.8, 0.0, 0.0);
    const PointCloud t = plate(17, 12, 1.1, 0.7, 0.05, 0.05);
    auto p = params(GetParam());
    if (auto* w = p.strategy.get<WendlandParameters>())
        w->supportRadius = 0.35;
    const auto mapping = buildMapping(p, s, t);
    Values mapped(t.rows(), 3);
    mapping->applyConsistent(linearField(s), mapped);
    EXPECT_LT(relativeMaxError(mapped, linearField(t)), 1e-10);
}

TEST_P(RbfMapping, ConservesTotalForceAndMoment)
{
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    const auto mapping = buildMapping(params(GetParam()), s, t);
    const Values g = faceForces(t.rows());
    Values f(s.rows(), 3);
    mapping->applyConservative(g, f);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    const double momentScale = forceScale * Values(t).rowwise().norm().maxCoeff();
    const double forceError = (f.colwise().sum() - g.colwise().sum()).norm() / forceScale;
    const double momentError = (totalMoment(s, f) - totalMoment(t, g)).norm() / momentScale;
    std::printf("%s: relative error of total force %.2e, of total moment %.2e\n",
                GetParam().c_str(), forceError, momentError);
    EXPECT_LT(forceError, 1e-12);
    EXPECT_LT(momentError, 1e-12);
}

TEST_P(RbfMapping, ConservativeIsTransposeOfConsistent)
{
    // <H u, g> == <u, H^T g> for arbitrary u, g (3 columns at once).
    const PointCloud s = solidCylinder(16), t = fluidCylinder(16);
    const auto mapping = buildMapping(params(GetParam()), s, t);
    const Values u = faceForces(s.rows() + 7).bottomRows(s.rows());
    const Values g = faceForces(t.rows());
    Values hu(t.rows(), 3), htg(s.rows(), 3);
    mapping->applyConsistent(u, hu);
    mapping->applyConservative(g, htg);
    const double lhs = (hu.array() * g.array()).sum(), rhs = (u.array() * htg.array()).sum();
    EXPECT_NEAR(lhs, rhs, 1e-12 * (std::abs(lhs) + hu.norm() * g.norm()));
}

INSTANTIATE_TEST_SUITE_P(Kinds, RbfMapping,
                         ::testing::Values("rbf-thin-plate", "rbf-wendland-c2", "rbf-pu"),
                         [](const auto& info)
                         {
                             if (info.param == "rbf-thin-plate")
                                 return std::string("ThinPlate");
                             return info.param == "rbf-pu" ? std::string("PartitionOfUnity")
                                                           : std::string("WendlandC2");
                         });

TEST(WendlandIterative, MatchesDirectAndKeepsTheExactProperties)
{
    // CG solves only to 1e-10, yet force, moment and linear fields stay exact: the polynomial
    // part never goes through the solver.
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    auto p = params("rbf-wendland-c2");
    p.strategy.get<WendlandParameters>()->solver = "direct";
    const auto direct = buildMapping(p, s, t);
    p.strategy.get<WendlandParameters>()->solver = "iterative";
    const auto iterative = buildMapping(p, s, t);
    const Values g = faceForces(t.rows());
    Values fd(s.rows(), 3), fi(s.rows(), 3), ui(t.rows(), 3), ud(t.rows(), 3);
    direct->applyConservative(g, fd);
    iterative->applyConservative(g, fi);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    const double momentScale = forceScale * Values(t).rowwise().norm().maxCoeff();
    EXPECT_LT((fi.colwise().sum() - g.colwise().sum()).norm() / forceScale, 1e-12);
    EXPECT_LT((totalMoment(s, fi) - totalMoment(t, g)).norm() / momentScale, 1e-12);
    EXPECT_LT((fi - fd).norm() / fd.norm(), 1e-8);
    iterative->applyConsistent(linearField(s), ui);
    EXPECT_LT(relativeMaxError(ui, linearField(t)), 1e-10);
    const Values smooth = linearField(s).array().sin();
    iterative->applyConsistent(smooth, ui);
    direct->applyConsistent(smooth, ud);
    EXPECT_LT((ui - ud).norm() / ud.norm(), 1e-8);
}

TEST(WendlandWithoutMpi, AutoUsesEigenAndMumpsIsAClearError)
{
    // This binary does not initialise MPI: auto falls back to Eigen's LDLT (direct up to
    // direct_max_points); solver mumps says what it needs.
    const PointCloud s = solidCylinder(16), t = fluidCylinder(16);
    auto p = params("rbf-wendland-c2");
    RbfWendlandC2 automatic(*p.strategy.get<WendlandParameters>());
    automatic.compute(s, t);
    EXPECT_EQ(automatic.solverInUse(), "direct");
    p.strategy.get<WendlandParameters>()->solver = "mumps";
    const std::string error = buildError(p, s, t);
    EXPECT_NE(error.find("solver mumps needs MPI"), std::string::npos) << "got: '" << error << "'";
}

TEST(NearestNeighbourMapping, ConservesForceAndMovesMomentByTheNodeOffsets)
{
    // Total force is conserved. The moment is conserved only where face centres and nodes
    // coincide: in general it changes by exactly sum_t (x_s(t) - x_t) x g_t.
    const PointCloud s = solidCylinder(24), t = fluidCylinder(24);
    const auto mapping = buildMapping(params("nearest-neighbour"), s, t);
    const Values g = faceForces(t.rows());
    Values f(s.rows(), 3);
    mapping->applyConservative(g, f);
    const double forceScale = g.cwiseAbs().colwise().sum().norm();
    EXPECT_LT((f.colwise().sum() - g.colwise().sum()).norm() / forceScale, 1e-12);

    const auto& nn = dynamic_cast<const NearestNeighbour&>(*mapping).nearestSource();
    PointCloud moved(t.rows(), 3);
    for (Eigen::Index i = 0; i < t.rows(); ++i)
        moved.row(i) = s.row(nn[static_cast<size_t>(i)]);
    const Eigen::Vector3d shift = totalMoment(moved, g) - totalMoment(t, g);
    const double momentScale = forceScale * Values(t).rowwise().norm().maxCoeff();
    EXPECT_LT((totalMoment(s, f) - totalMoment(t, g) - shift).norm() / momentScale, 1e-12);
    EXPECT_GT(shift.norm() / momentScale, 1e-5); // the caveat is real on non-matching meshes

    // Matched positions: moment conserved too.
    const auto same = buildMapping(params("nearest-neighbour"), s, s);
    const Values gs = faceForces(s.rows());
    Values fs(s.rows(), 3);
    same->applyConservative(gs, fs);
    EXPECT_LT((totalMoment(s, fs) - totalMoment(s, gs)).norm() / momentScale, 1e-12);
}

TEST(NearestNeighbourMapping, CopiesNearestValues)
{
    PointCloud s(3, 3), t(2, 3);
    s << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    t << 0.95, 0.05, 0, 0.05, 0.9, 0;
    const auto mapping = buildMapping(params("nearest-neighbour"), s, t);
    Values u(3, 1), v(2, 1);
    u << 10, 20, 30;
    mapping->applyConsistent(u, v);
    EXPECT_EQ(v(0, 0), 20);
    EXPECT_EQ(v(1, 0), 30);
}

TEST(MappingApply, RepeatedAndMultiColumnCallsAgree)
{
    const PointCloud s = solidCylinder(16), t = fluidCylinder(16);
    for (const char* type : {"nearest-neighbour", "rbf-thin-plate", "rbf-wendland-c2", "rbf-pu"})
    {
        const auto mapping = buildMapping(params(type), s, t);
        const Values u = linearField(s).array().sin();
        Values all(t.rows(), 3), one(t.rows(), 1), again(t.rows(), 3);
        mapping->applyConsistent(u, all);
        mapping->applyConsistent(u.col(1), one);
        mapping->applyConsistent(u, again);
        EXPECT_EQ((all - again).cwiseAbs().maxCoeff(), 0.0) << type;
        EXPECT_LT((all.col(1) - one).cwiseAbs().maxCoeff(), 1e-14) << type;
    }
}

TEST(MappingParameters, RejectsBadInputWithOneLineMessages)
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
    try
    {
        mappingType("rbf-quadratic");
        FAIL() << "an unknown mapping type was accepted";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_EQ(std::string(e.what()),
                  "mapping.type 'rbf-quadratic' is unknown; use one of "
                  "nearest-neighbour, rbf-thin-plate, rbf-wendland-c2, rbf-pu, nearest-projection, "
                  "moving-least-squares");
    }
    MappingParameters p;
    EXPECT_EQ(message(p), ""); // nearest-neighbour by default
    p = params("rbf-wendland-c2");
    p.strategy.get<WendlandParameters>()->supportRadius = 0.0;
    EXPECT_NE(message(p).find("rbf-wendland-c2.support_radius must be > 0 m"), std::string::npos);
    // Issue 15: numbers printed as 0.000000; %g keeps small values.
    p.strategy.get<WendlandParameters>()->supportRadius = -1e-7;
    EXPECT_NE(message(p).find("(got -1e-07)"), std::string::npos) << message(p);
    p.strategy.get<WendlandParameters>()->iterativeTolerance = 2.0;
    p.strategy.get<WendlandParameters>()->supportRadius = 1e-3;
    EXPECT_NE(message(p).find("rbf-wendland-c2.iterative_tolerance must be in (0, 1) (got 2)"),
              std::string::npos)
        << message(p);
    p = params("nearest-neighbour");
    p.overlapTolerance = -1;
    EXPECT_NE(message(p).find("mapping.overlap_tolerance must be > 0"), std::string::npos);
    EXPECT_EQ(message(params("rbf-thin-plate")), "");
}

TEST(MappingSetup, RefusesTooSmallSupportRadiusAndTooLargeDenseSystems)
{
    const PointCloud s = solidCylinder(16), t = fluidCylinder(16);
    auto p = params("rbf-wendland-c2");
    p.strategy.get<WendlandParameters>()->supportRadius =
        1e-5; // well below the node spacing (0.2 m)
    const std::string error = buildError(p, s, t);
    EXPECT_NE(error.find("has no source point within mapping.support_radius 1e-05 m"),
              std::string::npos)
        << "got: '" << error << "'";
    p = params("rbf-thin-plate");
    p.strategy.get<ThinPlateParameters>()->maxSourcePoints = 100;
    EXPECT_THROW(buildMapping(p, s, t), std::runtime_error);

    PointCloud duplicated = s;
    duplicated.row(5) = duplicated.row(3);
    EXPECT_THROW(buildMapping(params("rbf-thin-plate"), duplicated, t), std::runtime_error);
}
