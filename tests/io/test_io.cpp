// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/Archive.hpp"
#include "io/AtomicFile.hpp"
#include "io/CsvHistory.hpp"
#include "io/VtuWriter.hpp"
#include "mesh/GmshTestMeshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace fsi;
namespace fs = std::filesystem;

namespace
{
fs::path tempDir()
{
    auto dir = fs::temp_directory_path() / ("fsi_test_io_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}
std::string slurp(const fs::path& p)
{
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
std::string run(const std::string& cmd)
{
    std::string out;
    if (FILE* f = ::popen(cmd.c_str(), "r"))
    {
        char buf[512];
        while (std::fgets(buf, sizeof buf, f))
            out += buf;
        ::pclose(f);
    }
    return out;
}
} // namespace

TEST(AtomicFile, LeavesNoTemporary)
{
    const auto dir = tempDir() / "atomic";
    fs::create_directories(dir);
    io::writeFileAtomically((dir / "a.txt").string(), "hello\n");
    io::writeFileAtomically((dir / "a.txt").string(), "world\n");
    EXPECT_EQ(slurp(dir / "a.txt"), "world\n");
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir))
        files += e.is_regular_file();
    EXPECT_EQ(files, 1);
    EXPECT_THROW(io::writeFileAtomically("/nonexistent-dir-fsi/a.txt", "x"), std::runtime_error);
}

// Quadratic cells come out as VTK quadratic types; meshio (Debian's python3-meshio) reads
// them back with the same point data, in ASCII and binary.
TEST(VtuWriter, QuadraticCellsRoundTripThroughMeshio)
{
    for (auto cell : {fsi::testing::TestCell::Tet10, fsi::testing::TestCell::Hex20,
                      fsi::testing::TestCell::Hex27})
    {
        const auto file = fsi::testing::makeBlockMesh((tempDir() / "b.msh").string(), cell);
        const mesh::Mesh m = mesh::readGmsh(file, {"solid", {}}, true);
        std::vector<double> u(3 * m.numNodes());
        for (int n = 0; n < m.numNodes(); ++n)
            for (int i = 0; i < 3; ++i)
                u[3 * n + i] = (i + 1) * m.nodes(0, n) + 0.5 * m.nodes(2, n);
        std::vector<io::Vector6> nodal(m.numNodes(), io::Vector6::Constant(2.0)),
            cells(m.cells.size(), io::Vector6::Zero());
        for (bool binary : {false, true})
        {
            const auto vtu = tempDir() / (std::string(fsi::testing::testCellName(cell)) +
                                          (binary ? "_b.vtu" : "_a.vtu"));
            io::writeVtu(vtu.string(), m, {&u, &nodal, &cells}, binary);
            ASSERT_TRUE(fs::exists(vtu));
            // the file names its stress measure
            EXPECT_NE(slurp(vtu).find("cauchy_stress = Cauchy (true) stress sigma [Pa]"),
                      std::string::npos);
            const std::string expectedType = cell == fsi::testing::TestCell::Tet10 ? "tetra10"
                                             : cell == fsi::testing::TestCell::Hex20
                                                 ? "hexahedron20"
                                                 : "hexahedron27";
            // also checks the VTK node order: mid-edge / mid-face nodes at the VTK-defined
            // midpoints of their corners (straight-sided block)
            const std::string script =
                "import meshio,sys\nimport numpy as np\nm=meshio.read(sys.argv[1])\n"
                "u=m.point_data['displacement']\nx=m.points\nc=m.cells[0]\n"
                "err=abs(u[:,1]-(2*x[:,0]+0.5*x[:,2])).max()\n"
                "E={'tetra10':[(0,1),(1,2),(2,0),(0,3),(1,3),(2,3)],'hexahedron20':[(0,1),(1,2),(2,"
                "3),(3,0),(4,5),(5,6),(6,7),(7,4),(0,4),(1,5),(2,6),(3,7)]}\n"
                "E['hexahedron27']=E['hexahedron20']+[(0,3,7,4),(1,2,6,5),(0,1,5,4),(3,2,6,7),(0,1,"
                "2,3),(4,5,6,7),(0,1,2,3,4,5,6,7)]\n"
                "first=4 if c.type=='tetra10' else 8\n"
                "order=max(np.abs(x[cell[first+k]]-x[list(cell[list(e)])].mean(axis=0)).max() for "
                "cell in c.data for k,e in enumerate(E[c.type]))\n"
                "print(c.type, len(c.data), len(x), 'ok' if err<1e-10 else err, 'order-ok' if "
                "order<1e-12 else order, m.point_data['von_mises'].max())\n";
            std::ofstream(tempDir() / "read.py") << script;
            const std::string out = run("/usr/bin/python3 " + (tempDir() / "read.py").string() +
                                        " " + vtu.string() + " 2>&1");
            if (out.find("No module named") != std::string::npos || out.empty())
                GTEST_SKIP() << "meshio not available: " << out;
            std::ostringstream expect;
            expect << expectedType << " " << m.cells.size() << " " << m.numNodes()
                   << " ok order-ok 6.0";
            EXPECT_EQ(out.substr(0, expect.str().size()), expect.str()) << out;
        }
    }
}

TEST(VtuWriter, PvdAndCsv)
{
    const auto file =
        fsi::testing::makeBlockMesh((tempDir() / "c.msh").string(), fsi::testing::TestCell::Tet10);
    const mesh::Mesh m = mesh::readGmsh(file, {"solid", {}}, true);
    io::PvdSeries pvd((tempDir() / "s.pvd").string());
    pvd.add(0.0, "s_0.vtu");
    pvd.add(1.5, "s_1.vtu");
    pvd.write();
    const std::string text = slurp(tempDir() / "s.pvd");
    EXPECT_NE(text.find("timestep=\"1.5\" part=\"0\" file=\"s_1.vtu\""), std::string::npos);
    io::CsvHistory csv((tempDir() / "h.csv").string(), m, {"tip"}, {{1.0, 1.0, 1.0}}, {"R_x"});
    EXPECT_NEAR(csv.distance(0), 0.0, 1e-12);
    std::vector<double> u(3 * m.numNodes(), 0.25);
    csv.record(0.0, u, {-1.5});
    csv.record(2.0, u, {2.0});
    EXPECT_THROW(csv.record(3.0, u), std::invalid_argument);
    EXPECT_EQ(slurp(tempDir() / "h.csv"),
              "time,tip_ux,tip_uy,tip_uz,R_x\n0,2.500000000000e-01,2.500000000000e-01,"
              "2.500000000000e-01,-1.500000000000e+00\n"
              "2,2.500000000000e-01,2.500000000000e-01,2.500000000000e-01,2.000000000000e+00\n");
    EXPECT_NEAR(io::vonMisesStress((io::Vector6() << 1, 0, 0, 0, 0, 0).finished()), 1.0, 1e-15);
    EXPECT_NEAR(io::vonMisesStress((io::Vector6() << 0, 0, 0, 1, 0, 0).finished()), std::sqrt(3.0),
                1e-15);
}

// Prisms: VTK wedge types, corners (0, 1, 2) with the right-hand normal pointing away from
// (3, 4, 5) as VTK defines it, mid-edge / mid-face nodes at their VTK-defined positions. The
// ASCII file is parsed directly (meshio 5 reorders wedges and cannot read wedge15 from VTU).
TEST(VtuWriter, PrismsAsVtkWedges)
{
    if (std::system("/usr/bin/python3 -c 'import numpy' > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "numpy not available";
    const std::string script =
        "import sys, xml.etree.ElementTree as ET\nimport numpy as np\n"
        "a={d.get('Name'):np.array(d.text.split(),dtype=float) for d in "
        "ET.parse(sys.argv[1]).iter('DataArray')}\n"
        "x=a['Points'].reshape(-1,3); conn=a['connectivity'].astype(int); "
        "off=a['offsets'].astype(int); types=a['types'].astype(int)\n"
        "E=[(0,1),(1,2),(2,0),(3,4),(4,5),(5,3),(0,3),(1,4),(2,5),(0,1,4,3),(1,2,5,4),(2,0,3,5)]\n"
        "bad=0; start=0\n"
        "for end in off:\n"
        "  p=x[conn[start:end]]; start=end\n"
        "  if np.dot(np.cross(p[1]-p[0],p[2]-p[0]),p[3]-p[0])>=0: bad+=1\n"
        "  for k in range(6,len(p)):\n"
        "    if np.abs(p[k]-p[list(E[k-6])].mean(axis=0)).max()>1e-9: bad+=1\n"
        "print('type', types[0], len(off), 'bad=%d'%bad)\n";
    std::ofstream(tempDir() / "wedge.py") << script;
    for (int q : {0, 15, 18})
    {
        const auto file = fsi::testing::makePrismBlock((tempDir() / "p.msh").string(), q);
        const mesh::Mesh m = mesh::readGmsh(file, {"solid", {}}, true);
        const auto vtu = tempDir() / ("wedge" + std::to_string(q) + ".vtu");
        io::writeVtu(vtu.string(), m, {}, false);
        const std::string out = run("/usr/bin/python3 " + (tempDir() / "wedge.py").string() + " " +
                                    vtu.string() + " 2>&1");
        const std::string type = q == 0 ? "type 13 " : q == 15 ? "type 26 " : "type 32 ";
        EXPECT_EQ(out.rfind(type, 0), 0u) << out;
        EXPECT_NE(out.find("bad=0"), std::string::npos) << out;
    }
}

// The restart archive: exact round trip; a truncated or altered file and a missing entry are
// refused with the file named.
TEST(Archive, RoundTripAndDamageDetection)
{
    const auto file = (tempDir() / "state.bin").string();
    io::ArchiveWriter w;
    const std::vector<double> values{1.0, -2.5e-300, 3.0e300, 0.1};
    w.put("values", values);
    w.put("cells", std::vector<int>{3, 1, 2});
    w.put("time", 360.0);
    w.put("level", 12);
    w.putText("type", "iqn-ils");
    w.put("empty", std::vector<double>{});
    w.commit(file);
    {
        io::ArchiveReader r(file);
        EXPECT_EQ(r.doubles("values"), values);
        EXPECT_EQ(r.ints("cells"), (std::vector<int>{3, 1, 2}));
        EXPECT_EQ(r.scalar("time"), 360.0);
        EXPECT_EQ(r.integer("level"), 12);
        EXPECT_EQ(r.text("type"), "iqn-ils");
        EXPECT_TRUE(r.doubles("empty").empty());
        EXPECT_THROW(r.doubles("missing"), std::runtime_error);
        EXPECT_THROW(r.ints("values"), std::runtime_error); // wrong kind
    }
    const std::string bytes = slurp(file);
    const auto expectRefused = [&](const std::string& content, const char* what) {
        std::ofstream(file, std::ios::binary | std::ios::trunc) << content;
        try
        {
            io::ArchiveReader r(file);
            ADD_FAILURE() << what << " was accepted";
        }
        catch (const std::runtime_error& e)
        {
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    };
    expectRefused(bytes.substr(0, bytes.size() / 2), "a truncated archive");
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    expectRefused(flipped, "a flipped byte");
    expectRefused("", "an empty file");
    EXPECT_THROW(io::ArchiveReader((tempDir() / "none.bin").string()), std::runtime_error);
}
