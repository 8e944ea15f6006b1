// SPDX-License-Identifier: GPL-3.0-or-later
// Distributed assembly: the solver on all ranks of MPI_COMM_WORLD (METIS element partitions,
// each rank assembling its own cells) gives the same displacement as a one-rank solve on
// MPI_COMM_SELF, to solver tolerance; small strain, total Lagrangian with Newton, and a
// viscoelastic history over several accepted levels. Run with 2 ranks (label mpi).
#include "FeTestSupport.hpp"
#include "MpiEnvironment.hpp"

#include <gtest/gtest.h>

using namespace fsi;

namespace
{

double maxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
    double d = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        d = std::max(d, std::abs(a[i] - b[i]));
        scale = std::max(scale, std::abs(b[i]));
    }
    return d / scale;
}

mesh::Mesh beam(fsi::testing::TestCell cell)
{
    fsi::testing::BlockSpec spec;
    spec.size = {1.0, 0.1, 0.1};
    spec.cells = {cell == fsi::testing::TestCell::Tet10 ? 20 : 10, 2, 2};
    const auto file =
        fsi::testing::makeBlockMesh(fsi::testing::tempFile("mpi_beam.msh"), cell, spec);
    return mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true);
}

std::vector<double> solveOn(MPI_Comm comm, const mesh::Mesh& m, const material::Material& law,
                            const fe::ProblemDefinition& p, int levels, int& ownedCells)
{
    fe::StructuralSolver solver(comm, m, law, p);
    ownedCells = solver.ownedCells();
    for (int n = 0; n < levels; ++n)
    {
        const auto r = solver.solve({n * 0.5, n ? 0.5 : 0.0});
        EXPECT_TRUE(r.converged) << r.message;
        solver.acceptLevel();
    }
    return solver.displacement();
}

} // namespace

TEST(Parallel, SameAnswerAsOneRank)
{
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    struct Case
    {
        const char* name;
        fsi::testing::TestCell cell;
        material::Kinematics kinematics;
        bool viscoelastic;
        double load;
    };
    for (const Case& c : {Case{"Tet10 small strain", fsi::testing::TestCell::Tet10,
                               material::Kinematics::SmallStrain, false, -1e3},
                          Case{"Hex20 total Lagrangian", fsi::testing::TestCell::Hex20,
                               material::Kinematics::TotalLagrangian, false, -2e5},
                          Case{"Tet10 viscoelastic, 4 levels", fsi::testing::TestCell::Tet10,
                               material::Kinematics::SmallStrain, true, -1e3}})
    {
        const mesh::Mesh m = beam(c.cell);
        material::MaterialParameters mp = fsi::testing::elastic(1e9, 0.3);
        if (c.viscoelastic)
        {
            mp.type = "viscoelastic";
            mp.modulusBasis = "long-term";
            mp.pronyConvention = "long-term-gamma";
            mp.pronyCoefficients = {0.5, 0.3};
            mp.pronyTimes = {0.3, 3.0};
        }
        const auto law = material::makeMaterial(mp, c.kinematics);
        fe::ProblemDefinition p;
        p.kinematics = c.kinematics;
        p.clamped = {"x0"};
        p.wetted = "x1";
        p.forces.push_back({"x1", Eigen::Vector3d(0, c.load, 0.3 * c.load)});
        p.density = 1000;
        p.gravity = Eigen::Vector3d(0, 0, -9.81);
        p.newton.residualTolerance = 1e-12;
        const int levels = c.viscoelastic ? 4 : 1;
        int ownedParallel = 0, ownedSerial = 0;
        const auto parallel = solveOn(MPI_COMM_WORLD, m, *law, p, levels, ownedParallel);
        const auto serial = solveOn(MPI_COMM_SELF, m, *law, p, levels, ownedSerial);
        int total = 0;
        MPI_Allreduce(&ownedParallel, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        EXPECT_EQ(total, m.cells.size());
        EXPECT_EQ(ownedSerial, m.cells.size());
        if (ranks > 1) {
            EXPECT_LT(ownedParallel, m.cells.size());
        }
        const double diff = maxDifference(parallel, serial);
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        if (rank == 0)
            std::printf(
                "%-30s %d rank(s), %d of %d cells on rank 0: max |u_par - u_1| / max|u| = %.2e\n",
                c.name, ranks, ownedParallel, m.cells.size(), diff);
        EXPECT_LT(diff, 1e-9) << c.name;
    }
}
