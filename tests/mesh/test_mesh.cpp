// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/GmshTestMeshes.hpp"
#include "mesh/Mesh.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace fsi;
using fsi::testing::TestCell;

namespace
{
std::string tempPath(const std::string& name)
{
    auto dir =
        std::filesystem::temp_directory_path() / ("fsi_test_mesh_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}
std::string errorOf(const std::function<void()>& f)
{
    try
    {
        f();
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return "";
}
} // namespace

// The hard-coded node tables equal Gmsh's reference nodes, shape functions are nodal.
TEST(ReferenceElement, MatchesGmshAndIsNodal)
{
    gmsh::initialize(0, nullptr, false);
    for (int gmshType : {2, 9, 3, 16, 10, 4, 11, 5, 17, 12, 6, 18, 13})
    {
        mesh::CellType type;
        ASSERT_TRUE(mesh::cellTypeFromGmsh(gmshType, type));
        const auto& ref = mesh::ReferenceElement::get(type);
        std::string name;
        int dim, order, nn, np;
        std::vector<double> c;
        gmsh::model::mesh::getElementProperties(gmshType, name, dim, order, nn, c, np);
        ASSERT_EQ(nn, ref.numNodes()) << name;
        ASSERT_EQ(dim, ref.dim());
        for (int a = 0; a < nn; ++a)
            for (int k = 0; k < dim; ++k)
                EXPECT_DOUBLE_EQ(c[a * dim + k], ref.node(a)[k]) << name << " node " << a;
        Eigen::VectorXd N;
        Eigen::MatrixXd dN;
        for (int a = 0; a < nn; ++a)
        {
            ref.evaluate(ref.node(a), N, dN);
            for (int b = 0; b < nn; ++b)
                EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-12) << name;
            EXPECT_NEAR(dN.colwise().sum().norm(), 0.0, 1e-11) << name; // partition of unity
        }
    }
    gmsh::finalize();
}

TEST(GmshReader, ReadsV2AndV4WithGroups)
{
    for (double version : {2.2, 4.1})
        for (TestCell cell : {TestCell::Tet10, TestCell::Hex20, TestCell::Hex27, TestCell::Tet4})
        {
            fsi::testing::BlockSpec spec;
            spec.mshVersion = version;
            const std::string file = fsi::testing::makeBlockMesh(tempPath("block.msh"), cell, spec);
            const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "x1", "boundary"}}, true);
            const auto counts = m.cellTypeCounts();
            ASSERT_EQ(counts.size(), 1u);
            EXPECT_EQ(counts.begin()->first, fsi::testing::testCellName(cell));
            EXPECT_GT(m.surface("x0").faces.size(), 0);
            for (int node : m.surface("x1").nodes)
                EXPECT_NEAR(m.nodes(0, node), 1.0, 1e-12);
            double volume = 0.0;
            (void)volume;
            EXPECT_THROW(m.surface("nope"), std::runtime_error);
        }
}

TEST(GmshReader, MissingGroupIsOneLineNamingFileAndGroup)
{
    const std::string file = fsi::testing::makeBlockMesh(tempPath("g.msh"), TestCell::Tet10);
    const std::string msg = errorOf(
        [&] {
            mesh::readGmsh(file, {"solid", {"x0", "wetted"}}, true);
        });
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find("'wetted'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
    const std::string vol = errorOf([&] { mesh::readGmsh(file, {"body", {}}, true); });
    EXPECT_NE(vol.find("'body'"), std::string::npos) << vol;
    const std::string missing = errorOf(
        [&] {
            mesh::readGmsh(tempPath("none.msh"), {"solid", {}}, true);
        });
    EXPECT_NE(missing.find("none.msh"), std::string::npos) << missing;
}

// Issue 15: an empty .msh said "no volume physical group" instead of naming the problem.
TEST(GmshReader, EmptyOrNoMeshFileIsNamed)
{
    const std::string empty = tempPath("empty.msh");
    std::ofstream(empty).close();
    EXPECT_EQ(errorOf(
                  [&] {
                      mesh::readGmsh(empty, {"solid", {}}, true);
                  }),
              empty + ": the mesh file is empty; write the mesh again (e.g. gmsh -3 part.geo -o "
                      "part.msh)");
    const std::string header = tempPath("header.msh");
    std::ofstream(header) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    const std::string msg = errorOf([&] { mesh::readGmsh(header, {"solid", {}}, true); });
    EXPECT_EQ(msg.rfind(header + ": holds no mesh nodes", 0), 0u) << msg;
    const std::string dir = std::filesystem::path(header).parent_path().string();
    EXPECT_EQ(errorOf(
                  [&] {
                      mesh::readGmsh(dir, {"solid", {}}, true);
                  }),
              dir + ": is a directory, not a mesh file; give the .msh file");
}

TEST(GmshReader, InvertedCellIsAnError)
{
    // one Tet4 with a left-handed node order
    const std::string file = tempPath("inverted.msh");
    std::ofstream(file)
        << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"solid\"\n"
           "$EndPhysicalNames\n$Nodes\n4\n1 0 0 0\n2 0 1 0\n3 1 0 0\n4 0 0 1\n$EndNodes\n"
           "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n";
    const std::string msg = errorOf([&] { mesh::readGmsh(file, {"solid", {}}, true); });
    EXPECT_NE(msg.find("inverted"), std::string::npos) << msg;
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
}

TEST(Mesh, NearestNode)
{
    const std::string file = fsi::testing::makeBlockMesh(tempPath("n.msh"), TestCell::Hex8);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {}}, true);
    const int n = m.nearestNode(Eigen::Vector3d(0.49, 0.51, 1.2));
    EXPECT_NEAR((m.nodes.col(n) - Eigen::Vector3d(0.5, 0.5, 1.0)).norm(), 0.0, 1e-12);
}

// scripts/convert-mesh: an Abaqus C3D20 cube with an element set and two node sets becomes a
// .msh with a physical volume and two physical surfaces (boundary faces of the node sets).
TEST(ConvertMesh, AbaqusInpKeepsGroups)
{
    const std::string out = tempPath("converted.msh");
    const std::string cmd = "/usr/bin/python3 " FSI_SOURCE_DIR
                            "/scripts/convert-mesh " FSI_SOURCE_DIR
                            "/tests/mesh/abaqus_c3d20_cube.inp " +
                            out + " > /dev/null 2>&1";
    if (std::system("/usr/bin/python3 -c 'import meshio' > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "python3-meshio not installed";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const mesh::Mesh m = mesh::readGmsh(out, {"body", {"fixed", "load"}}, true);
    EXPECT_EQ(m.cellTypeCounts().at("Hex20"), 1);
    EXPECT_GT(m.minJacobian(0), 0.0);
    const auto& fixed = m.surface("fixed");
    ASSERT_EQ(fixed.faces.size(), 1);
    EXPECT_EQ(fixed.faces.types[0], mesh::CellType::Quad8);
    EXPECT_EQ(fixed.nodes.size(), 8u);
    for (int n : fixed.nodes)
        EXPECT_DOUBLE_EQ(m.nodes(0, n), 0.0);
    for (int n : m.surface("load").nodes)
        EXPECT_DOUBLE_EQ(m.nodes(0, n), 1.0);
}

TEST(GmshReader, Prisms)
{
    for (int q : {0, 15, 18})
    {
        const std::string file = fsi::testing::makePrismBlock(tempPath("prisms.msh"), q);
        const mesh::Mesh m = mesh::readGmsh(file, {"solid", {"x0", "boundary"}}, true);
        const std::string name = q == 0 ? "Prism6" : q == 15 ? "Prism15" : "Prism18";
        EXPECT_GT(m.cellTypeCounts().at(name), 0) << name;
    }
}
