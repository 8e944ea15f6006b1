// SPDX-License-Identifier: GPL-3.0-or-later
// nearest-projection: exact reproduction of the faces' interpolation space at points on the
// (curved) source surface, the value at the projection for points off it, conservation of force
// and moment by the transpose, and its one-line errors.
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

MappingParameters projection()
{
    MappingParameters p;
    p.strategy = mappingType("nearest-projection").defaults();
    return p;
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
    const PatchMesh mesh = patch(cylinder, 6, GetParam());
    const PointCloud targets = pointsOnFaces(mesh, 400, 7);
    const auto map = buildMapping(projection(), mesh.nodes, targets, &mesh.surface);
    Values mapped(targets.rows(), 3);
    map->applyConsistent(linearField(mesh.nodes), mapped);
    const double error = (mapped - linearField(targets)).cwiseAbs().maxCoeff();
    EXPECT_LT(error, 1e-10) << "largest error of a linear field at points on the faces";
    const auto* p = dynamic_cast<const NearestProjection*>(map.get());
    ASSERT_NE(p, nullptr);
    EXPECT_LT(p->maxDistance(), 1e-10) << "the targets lie on the faces";
}

TEST_P(NearestProjectionFaces, ConservesForceAndMomentOfForcesOnTheSurface)
{
    const PatchMesh mesh = patch(cylinder, 5, GetParam());
    const PointCloud targets = pointsOnFaces(mesh, 300, 11);
    const auto map = buildMapping(projection(), mesh.nodes, targets, &mesh.surface);
    std::mt19937 random(3);
    std::normal_distribution<double> normal;
    Values forces(targets.rows(), 3);
    for (Eigen::Index i = 0; i < forces.size(); ++i)
        forces.data()[i] = normal(random);
    Values nodal(mesh.nodes.rows(), 3);
    map->applyConservative(forces, nodal);
    const Eigen::Vector3d total = forces.colwise().sum().transpose();
    EXPECT_LT((nodal.colwise().sum().transpose() - total).norm(), 1e-11 * forces.norm());
    EXPECT_LT((totalMoment(mesh.nodes, nodal) - totalMoment(targets, forces)).norm(),
              1e-11 * forces.norm());
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
