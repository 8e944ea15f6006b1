// SPDX-License-Identifier: GPL-3.0-or-later
// Thin MUMPS (double, parallel) wrapper for the solid's tangent systems.
#pragma once

#include <mpi.h>

#include <memory>
#include <vector>

namespace fsi::linalg
{

// MUMPS ICNTL(7) values. Debian's MUMPS 5.5 has neither METIS nor SCOTCH compiled in:
// Metis is computed by this wrapper (METIS_NodeND -> PERM_IN); Scotch falls back to MUMPS'
// automatic choice.
enum class Ordering : int
{
    Amd = 0,
    Amf = 2,
    Scotch = 3,
    Pord = 4,
    Metis = 5,
    Qamd = 6,
    Automatic = 7
};

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
    // Symmetric only: when the values change but the pattern does not, first solve with
    // conjugate gradients preconditioned by the existing (stale) factorization; factorize only
    // when CG misses reuseTolerance within reuseMaxIterations, or needed more than
    // refactorAfterIterations (the factor is then refreshed for the next solves). Pays when the
    // matrix changes little between factorizations (a viscoelastic tangent whose dt changes).
    bool reuseFactorization = false;
    double reuseTolerance = 1e-10;    // |b - A x| <= tol |b|
    int reuseMaxIterations = 25;
    int refactorAfterIterations = 12;
};

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

    // Analysis if needed, then numerical factorization if stale; no-op otherwise.
    // Throws std::runtime_error with INFOG(1)/INFOG(2) and a hint (singular matrix:
    // "check the clamped boundary").
    void factorize();

    // Centralized: rank 0 passes the rhs (size n) and gets the solution in place;
    // other ranks' argument is ignored and left untouched. Calls factorize() first.
    void solve(std::vector<double>& rhsAndSolution);

    // Distributed-assembly helper: every rank passes its partial rhs (size n, its own
    // elements' contributions); they are summed onto rank 0, solved, and the solution
    // is returned on EVERY rank.
    void solveSummedRhs(std::vector<double>& partialRhsAndSolution);

    // Broadcast a rank-0 vector to all ranks (resized on the others).
    void broadcastFromRoot(std::vector<double>& vector) const;

    int analysisCount() const { return analysisCount_; }
    int factorizationCount() const { return factorizationCount_; }
    int solveCount() const { return solveCount_; }
    // Solves done by CG on a stale factorization (reuseFactorization) and their CG iterations.
    int reusedSolveCount() const { return reusedSolves_; }
    int reuseIterationCount() const { return reuseIterations_; }
    // Negative pivots of the last symmetric factorization (INFOG(12)); with an SPD
    // tangent expected, > 0 flags instability (buckling, limit point, inverted elements).
    int negativePivotCount() const { return negativePivots_; }
    // Entries in the factors of the last factorization (INFOG(29)): fill, for benchmarks.
    long long factorEntryCount() const { return factorEntries_; }
    int size() const { return n_; }
    MPI_Comm communicator() const { return comm_; }

private:
    void backSubstitute(std::vector<double>& rhsAndSolution); // rank 0 data, collective
    // y = A x with the current values (x significant on rank 0; y summed onto rank 0).
    void multiply(std::vector<double>& x, std::vector<double>& y) const;
    // CG preconditioned by the stale factorization; false (b untouched) when it misses the
    // tolerance. Collective; b/x significant on rank 0.
    bool solveWithStaleFactor(std::vector<double>& rhsAndSolution);
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
    bool valuesSet_ = false;
    bool analysed_ = false;
    bool factorized_ = false;
    int analysisCount_ = 0;
    int factorizationCount_ = 0;
    int solveCount_ = 0;
    int reusedSolves_ = 0;
    int reuseIterations_ = 0;
    bool refreshFactor_ = false; // the last CG needed many iterations: factorize next time
    int negativePivots_ = 0;
    long long factorEntries_ = 0;
};

} // namespace fsi::linalg
