// SPDX-License-Identifier: GPL-3.0-or-later
// The coupling loop on a real FE cantilever (Tet10, small strain) with a test-double fluid
// whose coupled fixed point is known in closed form (SpringBackFluid.hpp). Runs on 1 rank
// (unit) and 2 ranks (mpi): the solid is distributed, the fluid double lives on rank 0.
#include "SpringBackFluid.hpp"
#include "driver/CoupledDriver.hpp"
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"
#include "mesh/GmshTestMeshes.hpp"
#include "mesh/Mesh.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>

using namespace fsi;

namespace
{

int worldRank()
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

const mesh::Mesh& beamMesh()
{
    static mesh::Mesh mesh = [] {
        std::string file = "/tmp/fsi-driver-beam-" + std::to_string(::getpid()) + ".msh";
        // Every rank writes its own copy under its own pid: no race.
        fsi::testing::BlockSpec spec;
        spec.size = {1.0, 0.1, 0.1};
        spec.cells = {8, 2, 2};
        spec.structuredTets = false;
        fsi::testing::makeBlockMesh(file, fsi::testing::TestCell::Tet10, spec);
        auto m = mesh::readGmsh(file, {"solid", {"x0", "x1"}}, true);
        std::filesystem::remove(file);
        return m;
    }();
    return mesh;
}

material::MaterialParameters elastic(double K, double G)
{
    material::MaterialParameters p;
    p.type = "linear-elastic";
    p.bulkModulus = K;
    p.shearModulus = G;
    p.validate();
    return p;
}

fe::ProblemDefinition cantilever()
{
    fe::ProblemDefinition p;
    p.clamped = {"x0"};
    p.wetted = "x1";
    return p;
}

// Mean y-displacement of the wetted nodes under the SpringBackFluid's load pattern alone.
double meanTipResponse(const material::MaterialParameters& params, double totalForce)
{
    auto law = material::makeMaterial(params, material::Kinematics::SmallStrain);
    fe::StructuralSolver solid(MPI_COMM_WORLD, beamMesh(), *law, cantilever());
    const std::size_t n = solid.wettedNodes().size();
    fe::InterfaceLoads loads;
    loads.forces.assign(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        loads.forces[3 * i + 1] = totalForce / n;
    auto report = solid.solve({0.0, 0.0}, loads);
    EXPECT_TRUE(report.converged);
    const auto u = solid.wettedNodeDisplacements();
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i)
        sum += u[3 * i + 1];
    return sum / n;
}

driver::CouplingParameters couplingWith(const std::string& accelerator, double omega)
{
    driver::CouplingParameters p;
    p.maxIterations = 60;
    p.convergence.absoluteTolerance = 1e-13; // [m]; the tip moves ~1e-3 m
    p.acceleration.type = accelerator;
    p.acceleration.constant.relaxation = omega;
    p.acceleration.aitken.initialRelaxation = omega;
    p.acceleration.iqnIls.initialRelaxation = omega;
    p.mapping.type = "nearest-neighbour";
    return p;
}

struct CoupledResult
{
    driver::RunSummary summary;
    double meanUy = 0;
};

CoupledResult runCoupled(const material::MaterialParameters& params, driver::CouplingParameters coupling,
                         double totalForce, double kappa)
{
    auto law = material::makeMaterial(params, material::Kinematics::SmallStrain);
    fe::StructuralSolver solid(MPI_COMM_WORLD, beamMesh(), *law, cantilever());
    // Every rank holds the double (the peer is called collectively); only rank 0's data matter.
    auto fluid = std::make_unique<fsi::testing::SpringBackFluid>(solid.wettedNodeCoordinates(), totalForce, kappa);
    const std::string out = "/tmp/fsi-driver-test-" + std::to_string(::getpid());
    driver::CoupledDriver driver(MPI_COMM_WORLD, solid, fluid.get(), coupling, out,
                                 params.relaxationTimes());
    driver.setVerbose(false);
    CoupledResult r;
    r.summary = driver.run();
    const auto u = solid.wettedNodeDisplacements();
    for (std::size_t i = 0; i < u.size() / 3; ++i)
        r.meanUy += u[3 * i + 1];
    r.meanUy /= static_cast<double>(u.size() / 3);
    EXPECT_TRUE(fluid->finished);
    std::filesystem::remove_all(out);
    return r;
}

constexpr double K = 2.0e6, G = 1.0e6, F0 = 10.0; // [Pa], [Pa], [N]

} // namespace

// Plain iteration has the contraction factor -1.5: omega = 1 diverges, Aitken converges to the
// closed-form fixed point.
TEST(CoupledDriver, AitkenConvergesWherePlainIterationDiverges)
{
    const auto params = elastic(K, G);
    const double U1 = meanTipResponse(params, F0);
    ASSERT_GT(U1, 1e-4);
    const double kappa = 1.5 / U1;
    const double expected = U1 / (1 + kappa * U1);

    const auto aitken = runCoupled(params, couplingWith("aitken", 0.5), F0, kappa);
    EXPECT_NEAR(aitken.meanUy, expected, 1e-8 * std::abs(expected));
    EXPECT_LE(aitken.summary.couplingIterations, 12);

    try
    {
        runCoupled(params, couplingWith("constant", 1.0), F0, kappa);
        FAIL() << "omega = 1 must diverge on this problem";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("diverged"), std::string::npos) << e.what();
    }
    if (worldRank() == 0)
        std::printf("fixed point %.6e m: aitken %d coupling iterations\n", expected,
                    aitken.summary.couplingIterations);
}

// The map is affine of rank one: IQN-ILS is exact after one secant column.
TEST(CoupledDriver, IqnIlsSolvesAnAffineRankOneProblemInFewIterations)
{
    const auto params = elastic(K, G);
    const double U1 = meanTipResponse(params, F0);
    const double kappa = 1.5 / U1;
    const auto iqn = runCoupled(params, couplingWith("iqn-ils", 0.5), F0, kappa);
    EXPECT_NEAR(iqn.meanUy, U1 / (1 + kappa * U1), 1e-8 * U1);
    EXPECT_LE(iqn.summary.couplingIterations, 4);
}

// Quasi-steady semantics: the t = 0 level is the instantaneous elastic response, a level long
// after the longest relaxation time the long-term one (bulk elastic, shear relaxes).
TEST(CoupledDriver, ViscoelasticLevelsSpanInstantaneousAndLongTermResponses)
{
    material::MaterialParameters visco;
    visco.type = "viscoelastic";
    visco.bulkModulus = K;
    visco.shearModulus = G; // long-term
    visco.modulusBasis = "long-term";
    visco.pronyConvention = "long-term-gamma";
    visco.pronyCoefficients = {0.6, 0.4};
    visco.pronyTimes = {0.1, 10.0};
    visco.validate();

    const double U1inst = meanTipResponse(elastic(K, G * 2.0), F0);
    const double U1long = meanTipResponse(elastic(K, G), F0);
    const double kappa = 0.5 / U1long;

    auto coupling = couplingWith("aitken", 0.5);
    coupling.time.type = "list";
    coupling.time.times = {0.0, 1.0e9};
    const auto r = runCoupled(visco, coupling, F0, kappa);
    ASSERT_EQ(r.summary.history.size(), 2u);
    // history holds the watched quantities; the mean is taken from the logged solver state:
    // re-derive level values from the closed form and compare the final (long-term) state.
    EXPECT_NEAR(r.meanUy, U1long / (1 + kappa * U1long), 1e-7 * U1long);
    EXPECT_TRUE(r.summary.history[0].converged);

    // Level 0 alone: the instantaneous response.
    auto instantOnly = couplingWith("aitken", 0.5);
    instantOnly.time.type = "list";
    instantOnly.time.times = {0.0};
    const auto r0 = runCoupled(visco, instantOnly, F0, kappa);
    EXPECT_NEAR(r0.meanUy, U1inst / (1 + kappa * U1inst), 1e-7 * U1inst);
}
