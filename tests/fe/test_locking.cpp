// SPDX-License-Identifier: GPL-3.0-or-later
// Near incompressibility (nu = 0.4999): Cook's membrane in plane strain, E = 250, total shear
// F = 1. Hex20 (2x2x2 reduced) and Tet10 converge under refinement to the same value; the
// linear Hex8/Tet4 lock (shown for contrast). Prints the table.
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

using namespace fsi;

namespace
{

enum class Kind
{
    Tet4,
    Tet10,
    Hex8,
    Hex20
};

std::string cookMesh(Kind kind, int n)
{
    const bool hex = kind == Kind::Hex8 || kind == Kind::Hex20;
    const bool quadratic = kind == Kind::Tet10 || kind == Kind::Hex20;
    const std::string path = fsi::testing::tempFile("cook_" + std::to_string(int(kind)) + "_" +
                                                    std::to_string(n) + ".msh");
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("cook");
    const int p1 = gmsh::model::geo::addPoint(0, 0, 0), p2 = gmsh::model::geo::addPoint(48, 44, 0),
              p3 = gmsh::model::geo::addPoint(48, 60, 0), p4 = gmsh::model::geo::addPoint(0, 44, 0);
    const std::vector<int> l = {
        gmsh::model::geo::addLine(p1, p2), gmsh::model::geo::addLine(p2, p3),
        gmsh::model::geo::addLine(p3, p4), gmsh::model::geo::addLine(p4, p1)};
    const int s = gmsh::model::geo::addPlaneSurface({gmsh::model::geo::addCurveLoop(l)});
    for (int c : l)
        gmsh::model::geo::mesh::setTransfiniteCurve(c, n + 1);
    gmsh::model::geo::mesh::setTransfiniteSurface(s);
    if (hex)
        gmsh::model::geo::mesh::setRecombine(2, s);
    gmsh::vectorpair out;
    gmsh::model::geo::extrude({{2, s}}, 0, 0, 1, out, {1}, {}, hex);
    gmsh::model::geo::synchronize();
    // out: top, volume, sides of l[0..3]
    gmsh::model::addPhysicalGroup(3, {out[1].second}, 1);
    gmsh::model::setPhysicalName(3, 1, "solid");
    gmsh::model::addPhysicalGroup(2, {out[5].second}, 2);
    gmsh::model::setPhysicalName(2, 2, "clamped");
    gmsh::model::addPhysicalGroup(2, {out[3].second}, 3);
    gmsh::model::setPhysicalName(2, 3, "load");
    gmsh::model::addPhysicalGroup(2, {s, out[0].second}, 4);
    gmsh::model::setPhysicalName(2, 4, "faces");
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
    gmsh::model::mesh::generate(3);
    if (quadratic)
        gmsh::model::mesh::setOrder(2);
    gmsh::write(path);
    gmsh::finalize();
    return path;
}

double cookTip(Kind kind, int n, double nu)
{
    const mesh::Mesh m =
        mesh::readGmsh(cookMesh(kind, n), {"solid", {"clamped", "load", "faces"}}, true);
    const auto law =
        material::makeMaterial(fsi::testing::elastic(250.0, nu), material::Kinematics::SmallStrain);
    fe::ProblemDefinition p;
    p.clamped = {"clamped"};
    p.tractions.push_back({"load", Eigen::Vector3d(0, 1.0 / 16.0, 0)});
    fe::PrescribedDisplacement planeStrain;
    planeStrain.surface = "faces";
    planeStrain.value[2] = 0.0;
    p.displacements.push_back(planeStrain);
    p.newton.absoluteTolerance = 1e-14;
    fe::StructuralSolver solver(MPI_COMM_WORLD, m, *law, p);
    const auto r = solver.solve({0, 0});
    EXPECT_TRUE(r.converged) << r.message;
    const int c = m.nearestNode(Eigen::Vector3d(48, 60, 0));
    return solver.displacement()[3 * c + 1];
}

} // namespace

TEST(Locking, CookMembraneNearlyIncompressible)
{
    const std::vector<int> levels = {2, 4, 8, 16};
    const char* names[] = {"Tet4", "Tet10", "Hex8", "Hex20"};
    std::map<Kind, std::vector<double>> uy;
    for (Kind k : {Kind::Tet4, Kind::Tet10, Kind::Hex8, Kind::Hex20})
        for (int n : levels)
            uy[k].push_back(cookTip(k, n, 0.4999));
    const double ref = uy[Kind::Hex20].back();
    std::printf("Cook's membrane, plane strain, E = 250, nu = 0.4999, F = 1: u_y(C)\n");
    std::printf("  n x n    Tet4        Tet10       Hex8        Hex20      (rel. to Hex20 n=16)\n");
    for (std::size_t i = 0; i < levels.size(); ++i)
    {
        std::printf("  %2d      ", levels[i]);
        for (Kind k : {Kind::Tet4, Kind::Tet10, Kind::Hex8, Kind::Hex20})
            std::printf("%.5f %+5.1f%%  ", uy[k][i], 100 * (uy[k][i] - ref) / ref);
        std::printf("\n");
    }
    (void)names;
    // quadratic elements: converge (differences shrink) to a common value (< 1 %)
    for (Kind k : {Kind::Tet10, Kind::Hex20})
    {
        const auto& v = uy[k];
        EXPECT_LT(std::abs(v[3] - v[2]), std::abs(v[2] - v[1]));
        EXPECT_LT(std::abs(v[3] - ref) / ref, 0.01);
        EXPECT_LT(std::abs(v[1] - ref) / ref,
                  0.10); // within 10 % on a 4 x 4 mesh (singular corners)
    }
    // the linear elements lock: far too stiff on the 8 x 8 mesh
    EXPECT_LT(uy[Kind::Hex8][2], 0.8 * ref);
    EXPECT_LT(uy[Kind::Tet4][2], 0.8 * ref);
}
