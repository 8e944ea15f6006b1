// SPDX-License-Identifier: GPL-3.0-or-later
// nearest-projection: exact reproduction of the faces' interpolation space at points on the
// (curved) source surface, the value at the projection for points off it, conservation of force
// and moment by the transpose, its one-line errors, and with blend > 0 a continuous map inside a
// convex edge of the source.
#include "Clouds.hpp"

#include "mapping/Mapping.hpp"
#include "mapping/NearestProjection.hpp"
#include "mapping/Registry.hpp"
#include "mesh/ReferenceElement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <utility>

using namespace fsi::mapping;
using fsi::mapping::test::linearField;
using fsi::mapping::test::totalMoment;
using fsi::mesh::CellList;
using fsi::mesh::CellType;
using fsi::mesh::ReferenceElement;

namespace
{

using Surface = std::function<Eigen::Vector3d(double u, double v)>;

// A structured surface mesh of P(u, v), (u, v) in [0, 1]^2, with n x n cells: Tri6 (each cell
// split in two) or Quad8/Quad9. Nodes on a (2n + 1)^2 parametric grid, placed on P: the faces are
// curved where P is.
struct PatchMesh
{
    PointCloud nodes;
    SourceSurface surface;
};

PatchMesh patch(const Surface& P, int n, CellType type)
{
    const int m = 2 * n + 1;
    PatchMesh mesh;
    mesh.nodes.resize(m * m, 3);
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
            mesh.nodes.row(j * m + i) = P(double(i) / (m - 1), double(j) / (m - 1)).transpose();
    const auto id = [m](int i, int j) { return j * m + i; };
    for (int cj = 0; cj < n; ++cj)
        for (int ci = 0; ci < n; ++ci)
        {
            const int i = 2 * ci, j = 2 * cj;
            if (type == CellType::Tri6)
            {
                const int a[6] = {id(i, j),     id(i + 2, j),     id(i + 2, j + 2),
                                  id(i + 1, j), id(i + 2, j + 1), id(i + 1, j + 1)};
                const int b[6] = {id(i, j),         id(i + 2, j + 2), id(i, j + 2),
                                  id(i + 1, j + 1), id(i + 1, j + 2), id(i, j + 1)};
                mesh.surface.faces.add(type, a, 6);
                mesh.surface.faces.add(type, b, 6);
            }
            else
            {
                const int q[9] = {id(i, j),         id(i + 2, j), id(i + 2, j + 2),
                                  id(i, j + 2),     id(i + 1, j), id(i + 2, j + 1),
                                  id(i + 1, j + 2), id(i, j + 1), id(i + 1, j + 1)};
                mesh.surface.faces.add(type, q, type == CellType::Quad9 ? 9 : 8);
            }
        }
    return mesh;
}

// Points X(xi) on random faces of the discrete surface (exactly on it), seeded.
PointCloud pointsOnFaces(const PatchMesh& mesh, int count, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<int> anyFace(0, mesh.surface.faces.size() - 1);
    PointCloud points(count, 3);
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    for (int t = 0; t < count; ++t)
    {
        const int f = anyFace(random);
        const auto& ref = ReferenceElement::get(mesh.surface.faces.types[std::size_t(f)]);
        double a = unit(random), b = unit(random);
        Eigen::Vector3d xi;
        if (ref.isSimplex())
        {
            if (a + b > 1.0)
                a = 1.0 - a, b = 1.0 - b;
            xi = {a, b, 0.0};
        }
        else
            xi = {2.0 * a - 1.0, 2.0 * b - 1.0, 0.0};
        ref.evaluate(xi, N, dN);
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int k = 0; k < N.size(); ++k)
            x += N(k) * mesh.nodes.row(mesh.surface.faces.nodes(f)[k]).transpose();
        points.row(t) = x.transpose();
    }
    return points;
}

MappingParameters projection(double blend = 0.0)
{
    NearestProjectionParameters np;
    np.blend = blend;
    return MappingParameters(np);
}

// A quarter cylinder of radius 0.5 m, 1 m long: curved faces.
Eigen::Vector3d cylinder(double u, double v)
{
    const double angle = 0.5 * M_PI * u;
    return {0.5 * std::cos(angle), 0.5 * std::sin(angle), v};
}

} // namespace

class NearestProjectionFaces : public ::testing::TestWithParam<CellType>
{
};

TEST_P(NearestProjectionFaces, ReproducesLinearFieldsOnACurvedSurface)
{
    // blend or not: on the surface the closest face alone carries a point
    const PatchMesh mesh = patch(cylinder, 6, GetParam());
    const PointCloud targets = pointsOnFaces(mesh, 400, 7);
    for (const double blend : {0.0, 1.0})
    {
        const auto map = buildMapping(projection(blend), mesh.nodes, targets, &mesh.surface);
        Values mapped(targets.rows(), 3);
        map->applyConsistent(linearField(mesh.nodes), mapped);
        const double error = (mapped - linearField(targets)).cwiseAbs().maxCoeff();
        EXPECT_LT(error, 1e-10) << "largest error of a linear field on the faces, blend " << blend;
        const auto* p = dynamic_cast<const NearestProjection*>(map.get());
        ASSERT_NE(p, nullptr);
        EXPECT_LT(p->maxDistance(), 1e-10) << "the targets lie on the faces";
    }
}

TEST_P(NearestProjectionFaces, ConservesForceAndMomentOfForcesOnTheSurface)
{
    const PatchMesh mesh = patch(cylinder, 5, GetParam());
    const PointCloud targets = pointsOnFaces(mesh, 300, 11);
    std::mt19937 random(3);
    std::normal_distribution<double> normal;
    Values forces(targets.rows(), 3);
    for (Eigen::Index i = 0; i < forces.size(); ++i)
        forces.data()[i] = normal(random);
    const Eigen::Vector3d total = forces.colwise().sum().transpose();
    for (const double blend : {0.0, 1.0})
    {
        const auto map = buildMapping(projection(blend), mesh.nodes, targets, &mesh.surface);
        Values nodal(mesh.nodes.rows(), 3);
        map->applyConservative(forces, nodal);
        EXPECT_LT((nodal.colwise().sum().transpose() - total).norm(), 1e-11 * forces.norm());
        EXPECT_LT((totalMoment(mesh.nodes, nodal) - totalMoment(targets, forces)).norm(),
                  1e-11 * forces.norm())
            << "blend " << blend;
    }
}

INSTANTIATE_TEST_SUITE_P(Faces, NearestProjectionFaces,
                         ::testing::Values(CellType::Tri6, CellType::Quad8, CellType::Quad9),
                         [](const ::testing::TestParamInfo<CellType>& info)
                         { return ReferenceElement::get(info.param).name(); });

TEST(NearestProjection, ReproducesQuadraticFieldsOnAFlatTri6Patch)
{
    // straight-sided quadratic triangles hold every quadratic polynomial of x and y
    const PatchMesh mesh = patch(
        [](double u, double v) { return Eigen::Vector3d(2.0 * u, v, 0.0); }, 4, CellType::Tri6);
    const PointCloud targets = pointsOnFaces(mesh, 200, 5);
    const auto map = buildMapping(projection(), mesh.nodes, targets, &mesh.surface);
    const auto quadratic = [](const PointCloud& x)
    {
        Values q(x.rows(), 1);
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            q(i, 0) = x(i, 0) * x(i, 0) + 3.0 * x(i, 0) * x(i, 1) - x(i, 1) * x(i, 1) + 0.2;
        return q;
    };
    Values mapped(targets.rows(), 1);
    map->applyConsistent(quadratic(mesh.nodes), mapped);
    EXPECT_LT((mapped - quadratic(targets)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(NearestProjection, TakesTheValueAtTheProjectionOfAPointOffTheSurface)
{
    // a flat patch z = 0: a point at height d above (x, y) projects to (x, y, 0)
    const PatchMesh mesh =
        patch([](double u, double v) { return Eigen::Vector3d(u, v, 0.0); }, 3, CellType::Tri6);
    PointCloud above(3, 3), onPlane(3, 3);
    above << 0.31, 0.42, 0.002, 0.77, 0.15, -0.001, 0.5, 0.5, 0.003;
    onPlane = above;
    onPlane.col(2).setZero();
    const auto map = buildMapping(projection(), mesh.nodes, above, &mesh.surface);
    Values mapped(3, 3);
    map->applyConsistent(linearField(mesh.nodes), mapped);
    EXPECT_LT((mapped - linearField(onPlane)).cwiseAbs().maxCoeff(), 1e-12);
    const auto* p = dynamic_cast<const NearestProjection*>(map.get());
    ASSERT_NE(p, nullptr);
    EXPECT_NEAR(p->maxDistance(), 0.003, 1e-12);
}

TEST(NearestProjection, RefusesMissingOrUnusableSurfacesAndBadParameters)
{
    const PatchMesh mesh = patch(cylinder, 4, CellType::Tri6);
    const PointCloud targets = pointsOnFaces(mesh, 10, 1);
    try
    {
        buildMapping(projection(), mesh.nodes, targets);
        FAIL() << "no surface: expected an error";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("needs the source's surface faces"), std::string::npos)
            << e.what();
    }
    SourceSurface volume;
    const int tet[4] = {0, 1, 2, 5};
    volume.faces.add(CellType::Tet4, tet, 4);
    EXPECT_THROW(buildMapping(projection(), mesh.nodes, targets, &volume), std::runtime_error);
    SourceSurface stray;
    const int tri[3] = {0, 1, int(mesh.nodes.rows())};
    stray.faces.add(CellType::Tri3, tri, 3);
    EXPECT_THROW(buildMapping(projection(), mesh.nodes, targets, &stray), std::runtime_error);
    NearestProjectionParameters bad;
    bad.candidateFaces = 0;
    EXPECT_THROW(bad.validate(), std::runtime_error);
    NearestProjectionParameters negative;
    negative.blend = -0.5;
    EXPECT_THROW(negative.validate(), std::runtime_error);
}

TEST(NearestProjection, PointCloudStrategiesIgnoreTheSurface)
{
    const PatchMesh mesh = patch(cylinder, 3, CellType::Tri6);
    const PointCloud targets = pointsOnFaces(mesh, 50, 2);
    MappingParameters nn; // nearest-neighbour
    const auto with = buildMapping(nn, mesh.nodes, targets, &mesh.surface);
    const auto without = buildMapping(nn, mesh.nodes, targets);
    Values a(targets.rows(), 3), b(targets.rows(), 3);
    with->applyConsistent(linearField(mesh.nodes), a);
    without->applyConsistent(linearField(mesh.nodes), b);
    EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0);
}

namespace
{

// A convex 90 deg edge: the side y = 0 (z in [0, 1]) meets the top z = 1 (y in [0, 1]) along
// y = 0, z = 1; x in [0, 1] along the edge. The solid lies at y > 0, z < 1, as a foil's side
// meets its tip face. n cells across each of the two faces.
Eigen::Vector3d edgeSurface(double u, double v)
{
    if (u <= 0.5)
        return {v, 0.0, 2.0 * u};
    return {v, 2.0 * (u - 0.5), 1.0};
}

// Largest |value(b) - value(a)| / |b - a| between consecutive points of a path that crosses the
// edge's bisector inside the solid, 2 to 8 mm deep; the field is a rotation's u = w x x.
double largestSlopeAcrossTheBisector(double blend, CellType type, double* fieldGradient)
{
    const PatchMesh mesh = patch(edgeSurface, 8, type);
    const int samples = 601;
    PointCloud path(samples, 3);
    for (int i = 0; i < samples; ++i)
    {
        const double s = double(i) / (samples - 1);
        const double depthSide = 0.002 + 0.006 * s, depthTop = 0.008 - 0.006 * s;
        path.row(i) << 0.43, depthSide, 1.0 - depthTop;
    }
    const Eigen::Vector3d w(0.3, -0.2, 0.1); // rad: |grad u| = |w|
    *fieldGradient = w.norm();
    const auto rotation = [&w](const PointCloud& x)
    {
        Values u(x.rows(), 3);
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            u.row(i) = w.cross(Eigen::Vector3d(x.row(i).transpose())).transpose();
        return u;
    };
    const auto map = buildMapping(projection(blend), mesh.nodes, path, &mesh.surface);
    Values mapped(samples, 3);
    map->applyConsistent(rotation(mesh.nodes), mapped);
    double slope = 0.0;
    for (int i = 1; i < samples; ++i)
        slope = std::max(slope, (mapped.row(i) - mapped.row(i - 1)).norm() /
                                    (path.row(i) - path.row(i - 1)).norm());
    return slope;
}

} // namespace

TEST(NearestProjection, ClosestFaceAloneJumpsAcrossTheBisectorOfAConvexEdge)
{
    // the reason for blend: the two projections lie ~sqrt(2) 5 mm apart where the faces swap
    double gradient = 0.0;
    const double slope = largestSlopeAcrossTheBisector(0.0, CellType::Tri6, &gradient);
    EXPECT_GT(slope, 50.0 * gradient);
}

TEST(NearestProjection, BlendMakesTheMapContinuousAcrossTheBisectorOfAConvexEdge)
{
    // band ~ blend d_min wide: the slope stays a few |grad u| (measured 2.6 |grad u| with
    // blend 1 and 3.8 with blend 0.5, on both face types; 491 with the closest face alone)
    for (const CellType type : {CellType::Tri6, CellType::Quad8})
        for (const auto& [blend, bound] : {std::pair{1.0, 3.0}, std::pair{0.5, 4.5}})
        {
            double gradient = 0.0;
            const double slope = largestSlopeAcrossTheBisector(blend, type, &gradient);
            EXPECT_LT(slope, bound * gradient)
                << ReferenceElement::get(type).name() << ", blend " << blend;
        }
}

TEST(NearestProjection, BlendLeavesAPointAboveAFaceInteriorAtItsProjection)
{
    // far from the face's edges (more than sqrt(3) d for blend 1) no other face is near enough
    const PatchMesh mesh =
        patch([](double u, double v) { return Eigen::Vector3d(u, v, 0.0); }, 3, CellType::Tri6);
    PointCloud above(2, 3), onPlane(2, 3);
    above << 0.31, 0.42, 0.002, 0.5, 0.5, 0.003;
    onPlane = above;
    onPlane.col(2).setZero();
    const auto map = buildMapping(projection(1.0), mesh.nodes, above, &mesh.surface);
    Values mapped(2, 3);
    map->applyConsistent(linearField(mesh.nodes), mapped);
    EXPECT_LT((mapped - linearField(onPlane)).cwiseAbs().maxCoeff(), 1e-12);
}
