// SPDX-License-Identifier: GPL-3.0-or-later
// Quasi-static structural solver: equilibrium div(sigma) + rho b = 0 at each time level,
// Newton with the consistent tangent, MUMPS through linalg::SparseDirectSolver.
//
// Use by a coupling driver (all calls collective on the communicator):
//   fe::StructuralSolver solid(comm, mesh, *law, problem);
//   auto x = solid.wettedNodeCoordinates();               // 3 per wetted node [m], fixed order
//   for each time level (time t, dt):
//     do {                                                 // coupling iterations
//       fe::InterfaceLoads f{forcesAtWettedNodes};         // [N], same order as x
//       auto report = solid.solve({t, dt}, f);             // re-solvable: history untouched
//       if (!report.converged) ...                         // never silently accepted
//       auto u = solid.wettedNodeDisplacements();          // [m]
//     } while (!couplingConverged);
//     solid.acceptLevel();                                 // commits material history + state
//
// Level semantics: solve() may be called any number of times for the same level; each call
// starts from the last converged solution (warm start; for a linear problem -- small strain and
// a law linear in the strain -- a re-solve with new loads only is one linear solve with the
// level's tangent, no Newton loop and no tangent assembly) and evaluates the material with the
// history committed by the last acceptLevel(). acceptLevel() requires the last solve to have
// converged (throws otherwise). Loads given to solve() REPLACE those of the previous call.
//
// Cost of a linear problem (small strain, law linear in the strain) per solve: the tangent is
// never assembled cell by cell after the first level when the law's tangent is isotropic
// (lambda m m^T + mu diag(2, 2, 2, 1, 1, 1), every small-strain law here): it is
// lambda K_lambda + mu K_mu with both parts assembled once (memory: two extra value arrays of
// the matrix). A new dt changes the tangent: the solve runs CG preconditioned by the last
// factorization (linalg::DirectSolverOptions::reuseFactorization) and stops once the residual is
// a tenth of Newton's tolerance (residualTolerance * max(|f_ext|, |f_int|) + absoluteTolerance),
// then checks it with one residual assembly; that assembly evaluates stress = D(dt) strain + the
// point's stress at zero strain (built once per level: 6 doubles per integration point), not
// the law. By default the level-0 factorization serves the whole history (a shear modulus that
// drifted more than ProblemDefinition::refactorShearDrift, if set, is refactorized at the
// level's first solve). On a stale factor every linear solve first projects its right-hand side
// on the kept earlier solutions (of every level, with the isotropic parts; interfaceResponse()
// columns included), so CG starts closer (rememberSolve).
#pragma once
#include "fe/ElementKernel.hpp"
#include "fe/Settings.hpp"
#include "linalg/SparseDirectSolver.hpp"
#include "material/Material.hpp"
#include "mesh/Mesh.hpp"

#include <Eigen/Dense>
#include <mpi.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fsi::fe
{

struct SurfaceTraction
{
    std::string surface;
    Eigen::Vector3d traction = Eigen::Vector3d::Zero(); // [Pa] per reference area, dead load
};

struct SurfaceForce
{
    std::string surface;
    Eigen::Vector3d total = Eigen::Vector3d::Zero(); // [N], spread as a uniform traction
};

// What is fixed and loaded; every surface name must be a group of the mesh.
struct ProblemDefinition
{
    material::Kinematics kinematics = material::Kinematics::SmallStrain;
    Formulation formulation = Formulation::Displacement; // volumetric treatment of hexahedra
    double density = 0.0;                                // [kg/m^3]
    Eigen::Vector3d gravity = Eigen::Vector3d::Zero();   // [m/s^2]
    std::vector<std::string> clamped;                    // all dofs fixed
    std::string wetted;                                  // interface surface ("" = none)
    std::vector<PrescribedDisplacement> displacements;
    std::vector<SurfaceTraction> tractions;
    std::vector<SurfaceForce> forces;
    NewtonSettings newton;
    // MUMPS settings (ordering, BLR, refinement, threads, verbosity); symmetric and
    // reuseFactorization are set by the solver (reuse for linear problems).
    linalg::DirectSolverOptions linearSolver;
    // Linear problem with an isotropic law: refactorize the tangent at a level whose shear
    // modulus differs from the factorized one by more than this fraction (CG on the old factor
    // needs more iterations the more it drifted); 0 (default): never (CG on the first
    // factorization, as long as it converges within linalg::DirectSolverOptions::
    // refactorAfterIterations). With lambda K_lambda + mu K_mu the preconditioned spectrum lies
    // between the ratios of the moduli to the factorized ones (Rayleigh quotient of two positive
    // parts), so a drift of 30 % costs a few CG iterations, while a factorization costs 25-60
    // solve phases on the hydrofoil meshes (bench/solid-iteration/README.md).
    double refactorShearDrift = 0.0;
    // Linear problem with an isotropic law: the linear solutions on a stale factor are kept
    // (at most 12) with their products by the tangent's two parts, and every later solve, of any
    // level, first takes the part of its right-hand side in their span by projection (see
    // rememberSolve); false: kept for the level only, forgotten when dt changes (for
    // comparisons: bench/solid-iteration --no-recycle).
    bool recycleSolutions = true;
    bool printIterations = false; // rank 0 prints Newton progress
};

// Forces from the coupling: 3 per wetted node [N] in wettedNodeCoordinates() order
// (empty: none). Not scaled by the load factor.
struct InterfaceLoads
{
    std::vector<double> forces;
};

// Restart: what acceptLevel() committed. displacement, externalForces and loadFactor are the
// same on every rank; cells/history are one rank's part (the history of each of its cells, the
// cell's integration points x historySize doubles, in `cells` order), so that a restart may use
// another number of ranks.
struct CommittedState
{
    std::vector<double> displacement;   // 3 per node [m]
    std::vector<double> externalForces; // 3 per node [N], loads of the last accepted level
    double loadFactor = 0.0;
    std::vector<int> cells; // global cell ids owned by the rank that saved it
    std::vector<double> history;
};

struct SolveReport
{
    bool converged = false;
    int newtonIterations = 0;        // total over sub-steps
    int loadCuts = 0;                // 0: one step; k: 2^k sub-steps were needed
    double initialResidual = 0.0;    // [N], free dofs
    double finalResidual = 0.0;      // [N]
    double referenceForce = 0.0;     // [N], the rtol reference
    std::vector<double> residuals;   // per Newton iteration of the successful attempt
    std::string message;             // why it failed / how it converged
    double assemblySeconds = 0.0;    // wall time in element loops (residual + tangent)
    double linearSolveSeconds = 0.0; // wall time in MUMPS (analysis, factorization, solve)
};

class StructuralSolver
{
public:
    // mesh and law must outlive the solver (not owned). Throws std::runtime_error for groups
    // missing in the mesh or an over-/under-constrained setup. Rank 0 prints one warning line
    // (stderr) if cells of the mesh lock volumetrically for the law's Poisson's ratio
    // (lockingCellTypes()).
    StructuralSolver(MPI_Comm comm, const mesh::Mesh& mesh, const material::Material& law,
                     ProblemDefinition problem);
    ~StructuralSolver();

    // Equilibrium at level `step` with the configured loads times loadFactor plus the
    // interface forces. Warm-started; commits nothing. Collective.
    SolveReport solve(const material::TimeStep& step, const InterfaceLoads& interface = {},
                      double loadFactor = 1.0);
    // Commits the last converged solve (material history, displacement, loads). Throws if the
    // last solve did not converge.
    void acceptLevel();
    // Back to the last accepted state (e.g. after a failed coupling level).
    void rejectLevel();

    // True for a linear problem (small strain, law linear in the strain): the displacement is
    // affine in the loads at a fixed level, so interfaceResponse() applies.
    bool linearInLoads() const { return linearProblem_; }
    // The wetted nodes' displacement change under interface load changes, with the tangent of
    // the last converged solve's level: column j is P K^-1 P^T loadChanges.col(j) [m] for the
    // nodal load change [N] in column j (3 per wetted node, wettedNodeCoordinates() order).
    // No residual assembly and no state change: solve() and acceptLevel() see nothing of it.
    // Each column's linear solve stops at |K x - b| <= relativeTolerance |b| (CG on a stale
    // factorization; a current one solves exactly): relativeTolerance in (0, 1), e.g. 1e-2 for
    // a predictor. All columns share each MUMPS solve phase (linalg::SparseDirectSolver::
    // solveMany: the factor is read once per CG iteration, not once per column).
    // Collective; loadChanges the same on every rank.
    // Pre: linearInLoads() and the last solve() converged (throws std::logic_error otherwise).
    Eigen::MatrixXd interfaceResponse(const Eigen::MatrixXd& loadChanges, double relativeTolerance);
    // solve() and then interfaceResponse() in one call: the columns ride along with the solve's
    // Newton step (one lockstep solve, so one set of MUMPS solve phases for the step and the
    // columns: on a stale factor a CG iteration reads the factor once for all of them). The
    // same results to the tolerances asked. A solve that needs no Newton step of its own (its
    // start already converged) answers the columns after it, as interfaceResponse() does;
    // one that does not converge leaves responses empty. Collective.
    // Pre: linearInLoads() (throws std::logic_error otherwise); loadChanges and
    // relativeTolerance as for interfaceResponse().
    SolveReport solveWithResponse(const material::TimeStep& step, const InterfaceLoads& interface,
                                  const Eigen::MatrixXd& loadChanges, double relativeTolerance,
                                  Eigen::MatrixXd& responses);
    // Linear solves done by interfaceResponse() and solveWithResponse() since construction
    // (columns).
    int interfaceResponseColumns() const { return responseColumns_; }
    // This rank's part of the committed state (for a checkpoint).
    CommittedState committedState() const;
    // Collective. parts: the committedState() of every rank of the run that saved them (any
    // rank count; same mesh and material). Sets the committed and current state; throws
    // std::runtime_error when the parts do not fit this mesh/material.
    void restoreCommittedState(const std::vector<CommittedState>& parts);

    // Replicated on every rank.
    const std::vector<double>& displacement() const { return u_; } // 3 per node [m]
    std::vector<double> wettedNodeCoordinates() const;             // 3 per node [m]
    std::vector<double> wettedNodeDisplacements() const;           // 3 per node [m]
    const std::vector<int>& wettedNodes() const { return wettedNodes_; }
    // The wetted surface's faces with node indices into wettedNodes() (the order of
    // wettedNodeCoordinates()); empty without a wetted surface.
    mesh::CellList wettedFaces() const;
    // --- Results of the CURRENT state: the last converged solve, or, after acceptLevel() /
    // rejectLevel() / restoreCommittedState(), the last accepted level. An accepted level's
    // stress is that of its own solve (its history increment included): evaluating it after the
    // commit does not re-apply the level's relaxation step. Collective; replicated on every rank.

    // Nodal (volume-averaged) and cell-averaged Cauchy (true) stress, Voigt order xx yy zz xy yz
    // xz, tensor shear [Pa]. Small strain: the stress of the law; total Lagrangian:
    // sigma = J^-1 F S F^T, in the deformed configuration, given at the reference nodes/cells.
    void cauchyStress(std::vector<material::Vector6>& nodal,
                      std::vector<material::Vector6>& cells) const;

    struct NodalStressStrain
    {
        material::Vector6 stress; // Cauchy [Pa], as cauchyStress()
        material::Vector6 strain; // [-], tensor shear (eps_xy, not gamma_xy): small strain eps,
                                  // total Lagrangian Green-Lagrange E (reference configuration)
    };
    // Volume averages over the cells around each of `nodes` (node ids of the mesh), computed on
    // those cells only (cheap for a few watch points).
    std::vector<NodalStressStrain> stressAndStrainAt(const std::vector<int>& nodes) const;

    // Reaction force [N] on a surface group: the sum over its nodes of f_int - f_ext, the force
    // the supports exert on the body there (a node in two groups counts in both). For a clamped
    // group in equilibrium it balances the loads: sum over all supports = -(total load). On free
    // dofs the sum is the equilibrium residual (about 0). Throws std::runtime_error for a name
    // that is not a group of the mesh. After restoreCommittedState() it is NaN until the next
    // solve (the internal forces are not checkpointed).
    Eigen::Vector3d reactionForce(const std::string& surface) const;

    const mesh::Mesh& mesh() const { return mesh_; }
    int numDofs() const { return 3 * mesh_.numNodes(); }
    int numFreeDofs() const { return numFree_; }
    // The tangent's direct solver (timings, memory, BLR figures: statistics()).
    const linalg::SparseDirectSolver& linearSolver() const { return *linear_; }
    int factorizationCount() const;
    int analysisCount() const;
    // Element loops that computed cell tangents (a linear problem with an isotropic law: the
    // two parts of its tangent, once; otherwise one per Newton iteration).
    int elementTangentAssemblyCount() const { return elementTangentAssemblies_; }
    int rank() const { return rank_; }
    int ranks() const { return size_; }
    int ownedCells() const { return static_cast<int>(ownCells_.size()); }

private:
    SolveReport solveLevel(const material::TimeStep& step, const InterfaceLoads& interface,
                           double loadFactor);
    bool linearUpdate(const std::vector<double>& fTarget, SolveReport& report);
    // Linear problem: earlier linear solutions x (free dofs, replicated), Euclidean-
    // orthonormalized, at most kSolvesKept (the oldest dropped). A new rhs is first projected on
    // them (Galerkin with the current tangent K: x += X c, rhs -= K X c, c = (X^T K X)^-1 X^T rhs)
    // and only the rest goes to the linear solver: CG on a stale factor starts closer. With the
    // tangent's isotropic parts (lambda K_lambda + mu K_mu, linearTangentFromParts) each x keeps
    // K_lambda x and K_mu x, so K x of any later level's (lambda, mu) costs no product and the
    // solutions serve every later level (a creep history's solutions span few directions);
    // otherwise each keeps K x and they are forgotten when the tangent changes. Used on a stale
    // factor only (a current one solves exactly in one phase, and K x of a stiff problem carries
    // rounding of eps cond(K)). rememberSolve() costs one or two distributed products.
    // Collective; rhs and x replicated.
    void rememberSolve(std::vector<double> x);
    void projectOnSolves(std::vector<double>& rhs, std::vector<double>& x) const;
    static constexpr int kSolvesKept = 12;
    // y = P x for one isotropic part P (lambdaPart_ or muPart_, this rank's entries): summed over
    // the ranks, returned on every rank. Collective.
    void partProduct(const std::vector<double>& part, const std::vector<double>& x,
                     std::vector<double>& y) const;
    // interfaceResponse()'s columns: the checked load changes on the free dofs (column-major,
    // rank 0; empty elsewhere) and each column's allowance relativeTolerance |b_j|. Throws
    // std::invalid_argument for a wrong size or tolerance, std::runtime_error for non-finite
    // loads.
    struct ResponseColumns
    {
        std::vector<double> rhs;
        std::vector<double> allowances;
        int count = 0;
    };
    ResponseColumns responseColumns(const Eigen::MatrixXd& loadChanges,
                                    double relativeTolerance) const;
    // One lockstep solve of `leading` right-hand sides (rank 0; e.g. a Newton step, with
    // their allowances first) followed by the response columns; rhs holds every solution
    // afterwards, on every rank. Returns the response columns' wetted rows; on a stale factor
    // their solutions are kept for later solves (rememberSolve). Not timed
    // (the callers count linearSeconds_). Collective.
    Eigen::MatrixXd solveResponseColumns(std::vector<double>& rhs, std::vector<double> allowances,
                                         int leading, int count);
    // The wetted rows of `columns` solutions starting at column `first` of `solutions` (free
    // dofs, column-major, replicated).
    Eigen::MatrixXd wettedRowsOf(const std::vector<double>& solutions, int first,
                                 int columns) const;
    // The free equation of interface row r = 3 k + i (wetted node k, component i); -1 when
    // that dof is prescribed.
    int wettedEquation(Eigen::Index r) const
    {
        return equation_[3 * static_cast<std::size_t>(
                                 wettedNodes_[static_cast<std::size_t>(r / 3)]) +
                         static_cast<std::size_t>(r % 3)];
    }
    // A solveWithResponse() in progress: newton() answers it with its first linear solve.
    struct PendingResponse
    {
        const ResponseColumns* columns = nullptr;
        Eigen::MatrixXd* responses = nullptr;
        bool answered = false;
    };
    PendingResponse* pendingResponse_ = nullptr;
    // The Newton step K du = rhs (rhs on rank 0, du on every rank) with the pending response
    // columns in the same lockstep solve.
    void solveStepWithResponse(std::vector<double>& du, double allowance);
    bool assemble(const std::vector<double>& u, bool withMatrix, std::vector<double>& fint);
    // Linear problem, isotropic law: values_ = lambda K_lambda + mu K_mu for step_ (the parts
    // assembled at the first call). False when the law's tangent is not isotropic (then the
    // element loop assembles it).
    bool linearTangentFromParts();
    // Linear problem: stressOffsets_ hold the stress at zero strain of every own integration
    // point for `step` and the committed history, so that stress = D(dt) strain + offset (the
    // law is affine in the strain); the force-only assemblies of a level then evaluate no law.
    // Built at the first call for a step/history; false for a nonlinear problem.
    bool affineStressFor(const material::TimeStep& step);
    // This rank's first integration point's committed history (null: none): what a linear
    // law's tangent may depend on besides the step (linearLawTangent).
    const double* firstCommittedHistory() const;
    // The residual allowance of a linear solve inside Newton: a tenth of Newton's tolerance
    // for the reference force ref [N] (see the header comment).
    double linearSolveAllowance(double ref) const;
    void buildExternalLoads(double factor, const InterfaceLoads& interface,
                            std::vector<double>& f) const;
    void applyPrescribed(double factor, std::vector<double>& u) const;
    bool newton(const std::vector<double>& fext, double factor, std::vector<double>& u,
                SolveReport& report, bool lineSearch);
    // newton() with the configured line-search policy (Fallback: plain, then line search).
    bool newtonWithPolicy(const std::vector<double>& fext, double factor, std::vector<double>& u,
                          SolveReport& report);
    double freeNorm(const std::vector<double>& v) const;
    // Total Lagrangian: det F > 0 at every integration point of every cell (collective). A
    // law without its own check (St Venant-Kirchhoff) has equilibria in inverted configurations
    // that full Newton steps can reach.
    bool admissible(const std::vector<double>& u) const;
    // Material stress (law's measure) at integration point q of own cell k for the current state.
    material::Vector6 pointStress(std::size_t k, int q, const material::Vector6& strain) const;
    // Volume-weighted sums over own cells (all if cellFilter is empty) of the Cauchy stress and
    // strain; collective. nodal: 13 per node (stress 6, strain 6, volume); cellMeans: 6 per cell.
    void accumulateFields(const std::vector<char>& cellFilter, std::vector<double>& nodal,
                          std::vector<double>* cellMeans) const;

    MPI_Comm comm_;
    int rank_ = 0, size_ = 1;
    const mesh::Mesh& mesh_;
    const material::Material& law_;
    ProblemDefinition problem_;
    material::TimeStep step_{};

    std::vector<int> ownCells_;
    std::vector<std::size_t> quadOffset_; // per own cell into quad_
    std::vector<int> pointOffset_;        // per own cell: first integration point
    std::vector<double> quad_;
    std::vector<double> committedHistory_; // own points x historySize

    std::vector<int> equation_; // dof -> free equation number or -1
    int numFree_ = 0;
    std::vector<int> prescribedDofs_;
    std::vector<double> prescribedValues_;        // at load factor 1
    std::vector<std::pair<int, int>> fieldNodes_; // (node, index in problem_.displacements)
    std::vector<int> wettedNodes_;

    std::unique_ptr<linalg::SparseDirectSolver> linear_;
    struct Pattern;
    std::unique_ptr<Pattern> pattern_;
    std::vector<double> values_;
    // lambda and mu parts of a linear problem's tangent (values_ layout); empty: not built yet
    // or not applicable (isotropicPartsTried_).
    std::vector<double> lambdaPart_, muPart_;
    bool isotropicPartsTried_ = false;
    double muValues_ = 0.0, muFactorized_ = 0.0; // mu of values_ / of the last factorization
    int factorizationsSeen_ = 0;
    std::vector<double> stressOffsets_; // 6 per own point [Pa] (affineStressFor)
    material::Matrix6 affineTangent_ = material::Matrix6::Zero();
    material::TimeStep offsetsStep_{-1.0, -1.0};
    int historyVersion_ = 0, offsetsVersion_ = -1; // committed history changes / offsets built
    int elementTangentAssemblies_ = 0;
    int responseColumns_ = 0;
    // rememberSolve(): x, and K_lambda x / K_mu x (with parts) or K x (first product only)
    struct KeptSolves
    {
        long valuesVersion = -1; // without parts: linear_->valuesVersion() they belong to
        bool withParts = false;  // products of the isotropic parts (else K x)
        std::vector<std::vector<double>> x, firstProduct, secondProduct;
        Eigen::MatrixXd firstGram, secondGram; // X^T (first|second) product, symmetric
    } kept_;
    double lambdaValues_ = 0.0; // lambda of values_ (with muValues_)

    std::vector<double> u_, uCommitted_;
    std::vector<double> fextCommitted_;
    double factorCommitted_ = 0.0;
    std::vector<double> fextLast_;
    double factorLast_ = 0.0;
    double assemblySeconds_ = 0.0;
    double linearSeconds_ = 0.0;
    bool lastConverged_ = false;
    // Small strain + a law linear in the strain: re-solves of a level with new loads only are
    // one back-substitution with the level's factorization (linearUpdate).
    bool linearProblem_ = false;
    bool linearUpdateReady_ = false; // the last solve converged on this level's tangent
    // The current state u_ is an accepted level (stress from the accepted history) or the last
    // converged solve at solvedStep_ (stress from the committed history and the step).
    bool atAcceptedState_ = true;
    material::TimeStep solvedStep_{};
    std::vector<double> fintConverged_;     // f_int of the last converged Newton solve [N]
    std::vector<double> fintAtU_, fextAtU_; // f_int, f_ext of the current state [N]
    std::vector<double> fintCommitted_;     // ... of the last accepted level
};

} // namespace fsi::fe
