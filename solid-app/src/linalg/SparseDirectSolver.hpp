// SPDX-License-Identifier: GPL-3.0-or-later
// Thin MUMPS (double, parallel) wrapper for the solid's tangent systems.
#pragma once

#include <mpi.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fsi::linalg
{

// Fill-reducing orderings: MUMPS ICNTL(7) values, and PtScotch (not an ICNTL(7) value: the
// parallel analysis, ICNTL(28) = 2 with ICNTL(29) = 1). Metis is computed by this wrapper in
// every MUMPS build (METIS_NodeND on the graph compressed to supervariables, e.g. the 3 dofs
// of a node, handed over as PERM_IN, ICNTL(7) = 1): Debian's MUMPS has no METIS compiled in.
// Scotch and PtScotch need the ptscotch build of MUMPS (libmumps-ptscotch-dev, what
// cmake/FindMUMPS.cmake links when found); the plain build (libmumps-dev) falls back to MUMPS'
// automatic choice for Scotch and rejects PtScotch. All other orderings run sequentially on
// rank 0 (ICNTL(28) = 1), on any number of ranks.
enum class Ordering : int
{
    Amd = 0,
    Amf = 2,
    Scotch = 3,
    Pord = 4,
    Metis = 5,
    Qamd = 6,
    Automatic = 7,
    PtScotch = 8
};

// True when the linked MUMPS has SCOTCH/PT-SCOTCH compiled in (ptscotch build): needed by
// Ordering::PtScotch and by BLR (MUMPS clusters the BLR blocks of a front with SCOTCH; without
// METIS or SCOTCH inside MUMPS the clusters are arbitrary and BLR neither compresses nor stays
// accurate, so LowRank::Auto stays full-rank and LowRank::On is rejected).
bool mumpsHasScotch();
// True for the ptscotch build (Ordering::PtScotch).
bool mumpsHasPtScotch();

// Refinement stops at this normwise backward error |b - A x|_inf / (|A|_inf |x|_inf + |b|_inf)
// even above refinementTolerance: a backward-stable full-rank solve ends there (rounding), so
// further steps cannot lower the residual (ill-conditioned matrices: nu -> 0.5, slender parts).
constexpr double kRoundingBackwardError = 1e-14;

// Block low-rank (BLR) factorization, MUMPS ICNTL(35).
enum class LowRank : int
{
    Off = 0, // full-rank factorization (ICNTL(35) = 0)
    On = 1,  // BLR factorization and solve (ICNTL(35) = 2)
    Auto = 2 // On when the matrix has at least lowRankMinSize rows (and mumpsHasScotch()),
             // Off below
};

// Every field's default is the documented one (config/solid.example.yaml, linear_solver block;
// solid-app/src/linalg/README.md). validate() checks them (the constructor calls it).
struct DirectSolverOptions
{
    bool symmetric = true;         // symmetric matrix (LDL^T); false: general LU
    bool positiveDefinite = false; // with symmetric: SPD (SYM=1, no pivoting) instead of
                                   // general symmetric (SYM=2, pivoting; safe near instability).
                                   // SYM=1 has no null-pivot detection: a singular matrix is
                                   // caught only if a pivot is exactly 0 or < 0.
    int ordering = static_cast<int>(Ordering::Metis); // ICNTL(7)
    int memoryRelaxationPercent = 30;                 // ICNTL(14); raised on INFOG(1) = -9
    int verbosity = 0;                                // 0 silent ... 4 MUMPS diagnostics
    // BLR compression (ICNTL(35), ICNTL(36), CNTL(7)). The factor is approximate to about
    // lowRankTolerance (relative); every solve with a BLR factor is checked and refined (below).
    LowRank lowRank = LowRank::Off;
    int lowRankMinSize = 100000;    // Auto: BLR for n >= this
    double lowRankTolerance = 1e-9; // CNTL(7), the BLR dropping threshold
    bool lowRankUcfs = true;        // ICNTL(36): true = UCFS (compress before the solve of the
                                    // panel: fewer flops), false = UFSC (MUMPS' default)
    // Residual check after a BLR solve: iterative refinement x += A_BLR^-1 (b - A x) until
    // |b - A x| <= refinementTolerance |b|, at most maxRefinementSteps steps; when it misses,
    // the matrix is factorized again without BLR (and stays full-rank for this solver).
    double refinementTolerance = 1e-10;
    int maxRefinementSteps = 10;
    // Full-rank solves too: residual check and refinement (one sparse product per step; off:
    // a full-rank solve is returned as MUMPS gives it, as before).
    bool checkResidual = false;
    // BLAS (OpenBLAS) and OpenMP threads per MPI rank, set when the solver is created;
    // 0 = leave them to the environment (OPENBLAS_NUM_THREADS, OMP_NUM_THREADS).
    int threadsPerRank = 1;
    // Symmetric only: when the values change but the pattern does not, first solve with
    // conjugate gradients preconditioned by the existing (stale) factorization; factorize only
    // when CG misses reuseTolerance within reuseMaxIterations, or needed more than
    // refactorAfterIterations (the factor is then refreshed for the next solves). Pays when the
    // matrix changes little between factorizations (a viscoelastic tangent whose dt changes).
    bool reuseFactorization = false;
    double reuseTolerance = 1e-10; // |b - A x| <= tol |b|
    int reuseMaxIterations = 25;
    int refactorAfterIterations = 12;

    // The first value out of range: key as the solid config spells it (under linear_solver),
    // the value and the fix; nullopt when all are valid.
    struct Error
    {
        std::string key, value, fix;
    };
    std::optional<Error> firstError() const;
    // Throws std::invalid_argument, one line: "linear_solver.<key> = <value> is invalid: <fix>".
    void validate() const;
};

// Wall and CPU seconds of the phases (summed over the calls; CPU of this rank's process), and
// what MUMPS reported for the last analysis/factorization.
struct DirectSolverStatistics
{
    double analysisSeconds = 0.0, factorizationSeconds = 0.0, solveSeconds = 0.0;
    double analysisCpuSeconds = 0.0, factorizationCpuSeconds = 0.0, solveCpuSeconds = 0.0;
    double orderingSeconds = 0.0;        // part of analysisSeconds: this wrapper's METIS (rank 0)
    long long estimatedMemoryMb = 0;     // INFOG(17): total over ranks, full-rank estimate
    long long factorizationMemoryMb = 0; // INFOG(19): total over ranks, used by the factorization
    long long maxRankMemoryMb = 0;       // INFOG(18): largest rank
    double fullRankFlops = 0.0;          // RINFOG(3): elimination flops of a full-rank factor
                                         // (after analysis: the estimate RINFOG(1))
    double lowRankFlops = 0.0;           // RINFOG(14): flops of the BLR factorization (0: off)
    bool lowRankActive = false;          // the last factorization used BLR
    long long factorEntries = 0;         // INFOG(29): entries of the full-rank factor
    long long lowRankFactorEntries = 0;  // INFOG(35): entries kept by BLR (0: off)
    int lowRankFallbacks = 0;            // BLR solves that missed the tolerance -> full rank
    int refinementSteps = 0;             // total refinement steps over all solves
    double lastRelativeResidual = -1.0;  // |b - A x| / |b| of the last checked solve (-1: none)
    std::vector<double> lastResiduals;   // the last checked solve: before and after each step
    double lastBackwardError = -1.0;     // |b - A x|_inf / (|A|_inf |x|_inf + |b|_inf), last
    std::vector<double> lastBackwardErrors; // the same, before and after each step
};

// BLAS library in use and its thread count, e.g. "OpenBLAS 0.3.21 ... Haswell SINGLE_THREADED"
// ("reference or other BLAS" when it is not OpenBLAS). For logs and benchmarks.
std::string blasDescription();

// The options in the solid config's words, one line, e.g. "ordering metis, low_rank auto
// (>= 100000 rows, tolerance 1e-09, ucfs), refinement 1e-10 x 10, memory_relaxation 30 %,
// threads 1".
std::string describe(const DirectSolverOptions& options);

// Collective on comm: every rank calls every method (and the destructor, which must run
// before MPI_Finalize) in the same order. Argument errors (sizes, indices) are checked
// locally and must not differ between ranks; MUMPS errors are reported on every rank.
//
// Matrix input is distributed assembled triplets (ICNTL(18)=3): each rank passes its
// own (row, col, value) triplets, 0-BASED global indices in [0, n); duplicates (also
// across ranks) are summed. With symmetric == true the caller passes the full matrix
// (what an element assembler produces) or its lower triangle: entries with row < col are
// dropped. Right-hand side and solution are centralized on rank 0.
class SparseDirectSolver
{
public:
    explicit SparseDirectSolver(MPI_Comm comm, DirectSolverOptions options = {});
    ~SparseDirectSolver();
    SparseDirectSolver(const SparseDirectSolver&) = delete;
    SparseDirectSolver& operator=(const SparseDirectSolver&) = delete;

    // Global size n and this rank's triplet positions. Symbolic analysis (ordering) is
    // done at the next factorize(), and only if the pattern differs from the last one
    // on some rank (same pattern again: no new analysis, values kept). A changed pattern
    // unsets the values: call setValues() before the next factorize().
    void setPattern(int n, std::vector<int> rows, std::vector<int> cols);

    // Values in the same order as this rank's pattern (size == rows.size()). Marks the
    // factorization stale only if some value changed (bitwise) on some rank.
    void setValues(std::vector<double> values);

    // Symbolic analysis only, if the pattern changed (no values needed): statistics() then
    // holds MUMPS' estimates (memory INFOG(17), flops RINFOG(1)). For sizing runs.
    void analyze();

    // Analysis if needed, then numerical factorization if stale; no-op otherwise.
    // Throws std::runtime_error with INFOG(1)/INFOG(2) and a hint (singular matrix:
    // "check the clamped boundary").
    void factorize();

    // Centralized: rank 0 passes the rhs (size n) and gets the solution in place;
    // other ranks' argument is ignored and left untouched. Calls factorize() first.
    // residualAllowance (same units as b, >= 0; the same on every rank): a solve by CG on a stale
    // factor (reuseFactorization) may stop once |b - A x|_2 <= max(reuseTolerance |b|_2,
    // residualAllowance), e.g. a Newton step whose caller needs the residual below its own
    // tolerance only; |b|_2 <= residualAllowance gives x = 0 (nothing to do). Solves with a
    // current factor ignore it. A zero rhs gives x = 0 without a factorization.
    void solve(std::vector<double>& rhsAndSolution, double residualAllowance = 0.0);

    // Several right-hand sides at once: rank 0 passes `columns` rhs of size n, column-major
    // (size n x columns), and gets the solutions in place; the other ranks' argument is
    // ignored. With a current full-rank factor one MUMPS solve phase serves all columns (the
    // factor is read once); with a stale one (reuseFactorization) CG runs on every column in
    // lockstep, the factor applied to all unfinished columns in one solve phase. A column
    // fails over to a refactorization as in solve(); a BLR factor or checkResidual solves the
    // columns one by one (with their refinement). residualAllowances: one per column (>= 0,
    // the same on every rank), as in solve().
    void solveMany(std::vector<double>& rhsAndSolutions, int columns,
                   const std::vector<double>& residualAllowances);

    // Distributed-assembly helper: every rank passes its partial rhs (size n, its own
    // elements' contributions); they are summed onto rank 0, solved, and the solution
    // is returned on EVERY rank. residualAllowance as in solve().
    void solveSummedRhs(std::vector<double>& partialRhsAndSolution, double residualAllowance = 0.0);

    // reuseFactorization: the next solve factorizes the current values instead of running CG
    // on the stale factor (the caller knows the matrix drifted too far). Collective decision:
    // every rank calls it.
    void factorizeAtNextSolve() { refreshFactor_ = true; }

    // True when the values changed since the last factorization (collective): a solve() now
    // runs CG on the stale factor (reuseFactorization) or factorizes first.
    bool factorIsStale() const;
    // True when the next solve runs CG on the stale factorization (reuseFactorization, values
    // changed on some rank, pattern not, no factorization requested). Collective.
    bool cgOnStaleFactor() const;
    // Counts setValues() calls (collective, so the same on every rank): a caller's key for
    // work that holds for one matrix, e.g. solutions kept for later right-hand sides.
    long valuesVersion() const { return valuesVersion_; }

    // y = A x with the current values (collective): x significant on rank 0 (broadcast to the
    // others, so it is resized there), y returned on every rank.
    void multiplyAll(std::vector<double>& x, std::vector<double>& y) const;

    // Broadcast a rank-0 vector to all ranks (resized on the others).
    void broadcastFromRoot(std::vector<double>& vector) const;

    int analysisCount() const { return analysisCount_; }
    int factorizationCount() const { return factorizationCount_; }
    int solveCount() const { return solveCount_; }
    // MUMPS solve phases (forward and backward substitution with the factor): one per solve
    // with a current factor, one per CG iteration (+1) on a stale one, one per refinement step.
    int backSubstitutionCount() const { return backSubstitutions_; }
    // Solves done by CG on a stale factorization (reuseFactorization) and their CG iterations.
    int reusedSolveCount() const { return reusedSolves_; }
    int reuseIterationCount() const { return reuseIterations_; }
    // Negative pivots of the last symmetric factorization (INFOG(12)); with an SPD
    // tangent expected, > 0 flags instability (buckling, limit point, inverted elements).
    int negativePivotCount() const { return negativePivots_; }
    // Entries in the factors of the last factorization (INFOG(29)): fill, for benchmarks.
    long long factorEntryCount() const { return factorEntries_; }
    // Phase timings, memory and BLR figures (see DirectSolverStatistics).
    const DirectSolverStatistics& statistics() const { return stats_; }
    const DirectSolverOptions& options() const { return options_; }
    int size() const { return n_; }
    MPI_Comm communicator() const { return comm_; }

private:
    void backSubstitute(std::vector<double>& rhsAndSolution); // rank 0 data, collective
    // the same for `columns` right-hand sides, column-major (one MUMPS solve phase)
    void backSubstitute(double* rhsAndSolutions, int columns);
    // CG preconditioned by the stale factorization on every column, in lockstep (solve() is
    // the one-column case); false (b untouched) when a column misses the tolerance within
    // reuseMaxIterations or CG breaks down. Collective; b/x significant on rank 0.
    bool solveManyWithStaleFactor(std::vector<double>& b, int columns,
                                  const std::vector<double>& residualAllowances);
    // y = A x with the current values (x significant on rank 0; y summed onto rank 0).
    void multiply(std::vector<double>& x, std::vector<double>& y) const;
    // With a BLR factor: residual check and iterative refinement of x for b (rank 0 data);
    // true when |b - A x| <= refinementTolerance |b|. Collective.
    bool refine(const std::vector<double>& b, std::vector<double>& x);
    void analyse();
    void factorizeNumerically();
    struct Handle; // owns DMUMPS_STRUC_C (dmumps_c.h only in the .cpp)
    std::unique_ptr<Handle> handle_;
    MPI_Comm comm_;
    DirectSolverOptions options_;
    int n_ = 0;
    std::vector<int> rows_; // kept triplets, 1-based (MUMPS)
    std::vector<int> cols_;
    std::vector<int> keptIndex_;  // position of each kept triplet in the caller's order
    std::size_t callerCount_ = 0; // caller's triplet count (before the triangle filter)
    std::vector<double> values_;  // kept values
    bool patternChanged_ = true;  // local flags, reduced in factorize()
    bool valuesChanged_ = true;
    long valuesVersion_ = 0; // setValues() calls
    bool valuesSet_ = false;
    bool analysed_ = false;
    bool factorized_ = false;
    int analysisCount_ = 0;
    int factorizationCount_ = 0;
    int solveCount_ = 0;
    int reusedSolves_ = 0;
    int reuseIterations_ = 0;
    int backSubstitutions_ = 0;
    bool refreshFactor_ = false; // the last CG needed many iterations: factorize next time
    int negativePivots_ = 0;
    long long factorEntries_ = 0;
    bool matrixNormStale_ = true; // |A|_inf for the backward error (refine)
    double matrixNorm_ = 0.0;
    bool lowRankDisabled_ = false; // a BLR solve missed the tolerance: full rank from then on
    DirectSolverStatistics stats_;
};

} // namespace fsi::linalg
