// SPDX-License-Identifier: GPL-3.0-or-later
// Turek-Hron CSM1 through solid-app (cases/solid/csm1, total Lagrangian St Venant-Kirchhoff,
// Hex20 n = 2, the left end clamped on the cylinder arc): uy(A) within 1 % of -6.610e-2 m and
// ux(A) within 1 % of -7.187e-3 m. The finer levels run in scripts/verify csm1 (label long).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

TEST(Csm1, TipDisplacementWithinOnePercent)
{
    const fs::path dir =
        fs::temp_directory_path() / ("fsi_test_csm1_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string caseDir = FSI_SOURCE_DIR "/cases/solid/csm1";
    ASSERT_EQ(std::system(("gmsh -3 -order 2 -setnumber n 2 " + caseDir + "/csm1.geo -o " +
                           (dir / "csm1.msh").string() + " > /dev/null 2>&1")
                              .c_str()),
              0);
    fs::copy_file(caseDir + "/csm1.yaml", dir / "csm1.yaml", fs::copy_options::overwrite_existing);
    const std::string run = std::string(SOLID_APP) + " " + (dir / "csm1.yaml").string() +
                            " --out " + (dir / "out").string() + " > " + (dir / "log").string() +
                            " 2>&1";
    ASSERT_EQ(std::system(run.c_str()), 0);
    std::ifstream csv(dir / "out" / "history.csv");
    std::string line, last;
    while (std::getline(csv, line))
        last = line;
    double t, ux, uy, uz;
    ASSERT_EQ(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf", &t, &ux, &uy, &uz), 4) << last;
    std::printf("CSM1 (Hex20, n = 2): ux(A) = %.5e m (ref -7.187e-3, %+.2f %%), uy(A) = %.5e m "
                "(ref -6.610e-2, %+.2f %%)\n",
                ux, 100 * (ux + 7.187e-3) / -7.187e-3, uy, 100 * (uy + 6.610e-2) / -6.610e-2);
    EXPECT_NEAR(uy, -6.610e-2, 0.01 * 6.610e-2);
    EXPECT_NEAR(ux, -7.187e-3, 0.01 * 7.187e-3);
    EXPECT_NEAR(uz, 0.0, 1e-12);
}
