// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/GmshTestMeshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

fs::path dir()
{
    static const fs::path d = []
    {
        auto p = fs::temp_directory_path() / ("fsi_test_solid_app_" + std::to_string(::getpid()));
        fs::create_directories(p);
        fsi::testing::BlockSpec spec;
        spec.size = {1.0, 0.2, 0.2};
        spec.cells = {5, 1, 1};
        fsi::testing::makeBlockMesh((p / "block.msh").string(), fsi::testing::TestCell::Tet10,
                                    spec);
        // a mesh with one inverted tetrahedron
        std::ofstream(p / "inverted.msh")
            << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 2 \"x0\"\n3 1 "
               "\"solid\"\n"
               "$EndPhysicalNames\n$Nodes\n4\n1 0 0 0\n2 0 1 0\n3 1 0 0\n4 0 0 1\n$EndNodes\n"
               "$Elements\n2\n1 2 2 2 2 1 2 4\n2 4 2 1 1 1 2 3 4\n$EndElements\n";
        return p;
    }();
    return d;
}

const char* good = R"(solid:
  mesh: {file: block.msh, volume: solid, clamped: [x0], wetted: x1}
  material: {type: linear-elastic, E: 1.0e7, nu: 0.3, density: 1000}
  kinematics: total-lagrangian
  loads:
    gravity: [0, -9.81, 0]
    tractions: [{surface: x1, traction: [0, -1.0e3, 0]}]
  time: {dt: 0.5, end: 1.0, load_factor: [[0, 0.5], [1, 1]]}
  output:
    format: ascii
    watch: [{name: tip, point: [1.0, 0.1, 0.1]}]
)";

struct Result
{
    int status;
    std::string stderrText;
};

Result runApp(const std::string& configText, const std::string& name = "case.yaml")
{
    const fs::path cfg = dir() / name;
    std::ofstream(cfg) << configText;
    const fs::path err = dir() / (name + ".stderr");
    const std::string cmd = std::string(SOLID_APP) + " " + cfg.string() + " --out " +
                            (dir() / (name + ".out")).string() + " > " +
                            (dir() / (name + ".stdout")).string() + " 2> " + err.string();
    const int raw = std::system(cmd.c_str());
    std::ifstream in(err);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text};
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

// exit status != 0, stderr is exactly one line "error: <file>: ... <key> ..."
void expectOneLineError(const Result& r, const std::string& file, const std::string& key)
{
    EXPECT_NE(r.status, 0);
    ASSERT_FALSE(r.stderrText.empty());
    EXPECT_EQ(r.stderrText.find('\n'), r.stderrText.size() - 1) << "not one line: " << r.stderrText;
    EXPECT_EQ(r.stderrText.rfind("error: ", 0), 0u) << r.stderrText;
    EXPECT_NE(r.stderrText.find(file), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(key), std::string::npos) << r.stderrText;
}

} // namespace

TEST(SolidApp, GoodRunWritesEchoVtuPvdCsv)
{
    const Result r = runApp(good, "good.yaml");
    EXPECT_EQ(r.status, 0) << r.stderrText;
    const fs::path out = dir() / "good.yaml.out";
    for (const char* f : {"config.echo.yaml", "solid.pvd", "solid_00000.vtu", "solid_00002.vtu",
                          "history.csv", "levels.csv"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    std::ifstream csv(out / "history.csv");
    std::string line;
    int rows = 0;
    while (std::getline(csv, line))
        ++rows;
    EXPECT_EQ(rows, 4); // header + 3 levels
    std::ifstream so(dir() / "good.yaml.stdout");
    std::string text((std::istreambuf_iterator<char>(so)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("newton  1"), std::string::npos); // iterations and residuals printed
    EXPECT_NE(text.find("kinematics: total-lagrangian"), std::string::npos); // config echo
}

TEST(SolidApp, BadInputIsOneLineAndNonZeroExit)
{
    expectOneLineError(runApp(replaced(good, "material:", "materail:"), "typo.yaml"), "typo.yaml",
                       "'materail'");
    expectOneLineError(
        runApp(replaced(good, "  kinematics: total-lagrangian\n", ""), "missing.yaml"),
        "missing.yaml", "'kinematics'");
    expectOneLineError(runApp(replaced(good, "wetted: x1", "wetted: interface"), "group.yaml"),
                       "block.msh", "'interface'");
    expectOneLineError(runApp(replaced(good, "nu: 0.3", "nu: 0.5"), "nu.yaml"), "nu.yaml", "nu");
    expectOneLineError(runApp(replaced(good, "E: 1.0e7", "E: -1.0e7"), "negative.yaml"),
                       "negative.yaml", "E");
    expectOneLineError(
        runApp(
            replaced(good, "{type: linear-elastic, E: 1.0e7,",
                     "{type: viscoelastic, modulus_basis: long-term, prony: {convention: abaqus-g, "
                     "coefficients: [0.2], times: [0.0]}, E: 1.0e7,"),
            "tau.yaml"),
        "tau.yaml", "times");
    expectOneLineError(runApp(replaced(good, "dt: 0.5", "dt: -1"), "dt.yaml"), "dt.yaml", "dt");
    expectOneLineError(
        runApp(replaced(replaced(good, "block.msh", "inverted.msh"), "wetted: x1", "wetted: x0"),
               "inverted.yaml"),
        "inverted.msh", "inverted");
    expectOneLineError(runApp(replaced(good, "E: 1.0e7", "E: [1]"), "type.yaml"), "type.yaml",
                       "must be a number");
    expectOneLineError(runApp(replaced(good, "block.msh", "nothere.msh"), "nomesh.yaml"),
                       "nothere.msh", "cannot open");
}

TEST(SolidApp, UsageErrors)
{
    const int raw = std::system((std::string(SOLID_APP) + " > /dev/null 2>&1").c_str());
    EXPECT_NE(WEXITSTATUS(raw), 0);
    const int raw2 =
        std::system((std::string(SOLID_APP) + " a.yaml --bogus > /dev/null 2>&1").c_str());
    EXPECT_NE(WEXITSTATUS(raw2), 0);
}

// solid.element.type reaches the solver: a nearly incompressible Hex27 bar prints one locking
// warning with the displacement element and none with projected-dilatation, which is softer.
TEST(SolidApp, ElementTypeAndLockingWarning)
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.2, 0.2};
    spec.cells = {4, 2, 2};
    fsi::testing::makeBlockMesh((dir() / "hex27.msh").string(), fsi::testing::TestCell::Hex27,
                                spec);
    const std::string base = R"(solid:
  mesh: {file: hex27.msh, volume: solid, clamped: [x0]}
  material: {type: linear-elastic, E: 1.0e7, nu: 0.4999}
  kinematics: small-strain
  element: {type: displacement}
  loads: {tractions: [{surface: x1, traction: [0, -1.0e3, 0]}]}
  output: {vtu: false, watch: [{name: tip, point: [1.0, 0.1, 0.1]}]}
)";
    auto tipUy = [](const std::string& name) // history.csv: time,tip_ux,tip_uy,tip_uz
    {
        std::ifstream csv(dir() / (name + ".out") / "history.csv");
        std::string header, time, ux, uy;
        std::getline(csv, header);
        std::getline(csv, time, ',');
        std::getline(csv, ux, ',');
        std::getline(csv, uy, ',');
        return std::stod(uy);
    };
    const Result plain = runApp(base, "hex27-plain.yaml");
    EXPECT_EQ(plain.status, 0) << plain.stderrText;
    EXPECT_EQ(plain.stderrText.rfind("warning: ", 0), 0u) << plain.stderrText;
    EXPECT_NE(plain.stderrText.find("Hex27"), std::string::npos) << plain.stderrText;
    EXPECT_EQ(plain.stderrText.find('\n'), plain.stderrText.size() - 1) << plain.stderrText;
    const Result pd =
        runApp(replaced(base, "type: displacement", "type: projected-dilatation"), "hex27-pd.yaml");
    EXPECT_EQ(pd.status, 0) << pd.stderrText;
    EXPECT_EQ(pd.stderrText, "");
    const double uPlain = tipUy("hex27-plain.yaml"), uPd = tipUy("hex27-pd.yaml");
    std::printf("Hex27 bar, nu = 0.4999: tip u_y displacement %.6e, projected-dilatation %.6e\n",
                uPlain, uPd);
    EXPECT_LT(uPd, uPlain); // both negative: the projected element is softer
}
