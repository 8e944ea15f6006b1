// SPDX-License-Identifier: GPL-3.0-or-later
#include "linalg/SparseDirectSolver.hpp"

#include <dmumps_c.h>
#include <metis.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace fsi::linalg
{

struct SparseDirectSolver::Handle
{
    DMUMPS_STRUC_C id{};
    std::vector<int> permutation; // PERM_IN on rank 0 (1-based positions), METIS ordering
    int& icntl(int i) { return id.icntl[i - 1]; }
    int infog(int i) const { return id.infog[i - 1]; }
};

namespace
{
constexpr int jobInit = -1, jobEnd = -2, jobAnalyse = 1, jobFactorize = 2, jobSolve = 3;

int rankOf(MPI_Comm comm)
{
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    return rank;
}

bool isWorkspaceError(int code)
{
    return code == -8 || code == -9 || code == -14 || code == -15 || code == -17 || code == -20;
}

std::string meaning(int code, int detail)
{
    switch (code)
    {
    case -5:
    case -7:
    case -13:
    case -19:
        return "out of memory (" + std::to_string(detail) +
               " units requested); use more ranks or a coarser mesh";
    case -6:
        return "the matrix is structurally singular (rank " + std::to_string(detail) +
               "); check the clamped boundary (rigid-body modes) and dofs without elements";
    case -10:
        return "the matrix is numerically singular (" + std::to_string(detail) +
               " pivots eliminated); check the clamped boundary (rigid-body modes)";
    case -40:
        return "the matrix was declared positive definite but a pivot <= 0 was met; set "
               "positiveDefinite = false (instability, inverted elements?)";
    case -16:
        return "N = " + std::to_string(detail) + " is out of range";
    case -2:
        return "NNZ = " + std::to_string(detail) + " is out of range";
    case -4:
        return "the METIS permutation handed to MUMPS is invalid (internal error)";
    default:
        if (isWorkspaceError(code))
            return "workspace too small even after raising ICNTL(14)";
        return "see the MUMPS user guide, INFOG(1) = " + std::to_string(code);
    }
}

// Symmetric adjacency (no diagonal) of the gathered 1-based triplets, METIS_NodeND, and
// PERM_IN(i) = position of variable i in the pivot order (1-based) = METIS iperm + 1.
std::vector<int> metisOrdering(int n, const std::vector<int>& rows, const std::vector<int>& cols)
{
    std::vector<std::pair<int, int>> edges;
    edges.reserve(2 * rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
        if (rows[k] != cols[k])
        {
            edges.emplace_back(rows[k] - 1, cols[k] - 1);
            edges.emplace_back(cols[k] - 1, rows[k] - 1);
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<int> permutation(n);
    if (edges.empty())
    {
        std::iota(permutation.begin(), permutation.end(), 1);
        return permutation;
    }
    std::vector<idx_t> xadj(n + 1, 0), adjncy(edges.size());
    for (std::size_t k = 0; k < edges.size(); ++k)
    {
        ++xadj[edges[k].first + 1];
        adjncy[k] = edges[k].second;
    }
    for (int i = 0; i < n; ++i)
        xadj[i + 1] += xadj[i];
    idx_t nv = n;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    std::vector<idx_t> perm(n), iperm(n);
    if (METIS_NodeND(&nv, xadj.data(), adjncy.data(), nullptr, options, perm.data(),
                     iperm.data()) != METIS_OK)
        throw std::runtime_error("SparseDirectSolver: METIS_NodeND ordering failed");
    for (int i = 0; i < n; ++i)
        permutation[i] = static_cast<int>(iperm[i]) + 1;
    return permutation;
}

// Gathers all ranks' int vectors on rank 0 (empty elsewhere).
std::vector<int> gatherOnRoot(const std::vector<int>& local, MPI_Comm comm)
{
    int size = 1;
    MPI_Comm_size(comm, &size);
    const int count = static_cast<int>(local.size());
    std::vector<int> counts(size), displacements(size, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    std::vector<int> all;
    if (rankOf(comm) == 0)
    {
        for (int r = 1; r < size; ++r)
            displacements[r] = displacements[r - 1] + counts[r - 1];
        all.resize(displacements.back() + counts.back());
    }
    MPI_Gatherv(local.data(), count, MPI_INT, all.data(), counts.data(), displacements.data(),
                MPI_INT, 0, comm);
    return all;
}
} // namespace

SparseDirectSolver::SparseDirectSolver(MPI_Comm comm, DirectSolverOptions options)
    : handle_(std::make_unique<Handle>()), comm_(comm), options_(options)
{
    DMUMPS_STRUC_C& id = handle_->id;
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id.par = 1; // the host works too
    id.sym = !options.symmetric ? 0 : (options.positiveDefinite ? 1 : 2);
    id.job = jobInit;
    dmumps_c(&id);
    if (id.infog[0] < 0)
        throw std::runtime_error("SparseDirectSolver: MUMPS initialisation failed, INFOG(1) = " +
                                 std::to_string(id.infog[0]));
    const bool talk = options.verbosity > 0;
    handle_->icntl(1) = talk ? 6 : -1; // error stream
    handle_->icntl(2) = talk ? 6 : -1; // diagnostics
    handle_->icntl(3) = talk ? 6 : -1; // global information
    handle_->icntl(4) = options.verbosity;
    handle_->icntl(5) = 0;  // assembled format
    handle_->icntl(18) = 3; // distributed assembled triplets
    handle_->icntl(20) = 0; // dense centralized rhs
    handle_->icntl(21) = 0; // centralized solution
    handle_->icntl(28) = 1; // sequential analysis (ordering below)
    const bool metis = options.ordering == static_cast<int>(Ordering::Metis);
    handle_->icntl(7) = metis ? 1 : options.ordering; // METIS: our own, as PERM_IN
    handle_->icntl(14) = options.memoryRelaxationPercent;
    handle_->icntl(24) = 1;      // null pivot detection: singular -> INFOG(28) > 0
    handle_->id.cntl[2] = 1e-12; // CNTL(3): |pivot row| <= 1e-12 ||A|| counts as null
}

SparseDirectSolver::~SparseDirectSolver()
{
    handle_->id.job = jobEnd;
    dmumps_c(&handle_->id);
}

void SparseDirectSolver::setPattern(int n, std::vector<int> rows, std::vector<int> cols)
{
    if (n < 1 || rows.size() != cols.size())
        throw std::invalid_argument("SparseDirectSolver::setPattern: n < 1 or rows/cols differ "
                                    "in length");
    std::vector<int> keptRows, keptCols, keptIndex;
    keptRows.reserve(rows.size());
    keptCols.reserve(rows.size());
    keptIndex.reserve(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
        if (rows[k] < 0 || rows[k] >= n || cols[k] < 0 || cols[k] >= n)
            throw std::invalid_argument("SparseDirectSolver::setPattern: entry (" +
                                        std::to_string(rows[k]) + ", " + std::to_string(cols[k]) +
                                        ") outside [0, " + std::to_string(n) + ")");
        if (options_.symmetric && rows[k] < cols[k])
            continue;
        keptRows.push_back(rows[k] + 1);
        keptCols.push_back(cols[k] + 1);
        keptIndex.push_back(static_cast<int>(k));
    }
    const bool same = n == n_ && rows.size() == callerCount_ && keptRows == rows_ &&
                      keptCols == cols_ && keptIndex == keptIndex_;
    if (same)
        return;
    patternChanged_ = true;
    n_ = n;
    callerCount_ = rows.size();
    rows_ = std::move(keptRows);
    cols_ = std::move(keptCols);
    keptIndex_ = std::move(keptIndex);
    values_.clear();
    valuesSet_ = false;
    valuesChanged_ = true;
}

void SparseDirectSolver::setValues(std::vector<double> values)
{
    if (values.size() != callerCount_)
        throw std::invalid_argument(
            "SparseDirectSolver::setValues: " + std::to_string(values.size()) +
            " values for a pattern of " + std::to_string(callerCount_) + " entries");
    std::vector<double> kept(keptIndex_.size());
    for (std::size_t k = 0; k < keptIndex_.size(); ++k)
        kept[k] = values[keptIndex_[k]];
    const bool same = valuesSet_ && kept.size() == values_.size() &&
                      std::memcmp(kept.data(), values_.data(), kept.size() * sizeof(double)) == 0;
    valuesSet_ = true;
    if (same)
        return;
    values_ = std::move(kept);
    valuesChanged_ = true;
}

void SparseDirectSolver::factorize()
{
    int local[3] = {patternChanged_ ? 1 : 0, valuesChanged_ ? 1 : 0, valuesSet_ ? 0 : 1};
    int global[3];
    MPI_Allreduce(local, global, 3, MPI_INT, MPI_MAX, comm_);
    if (global[2])
        throw std::logic_error("SparseDirectSolver::factorize: setValues() not called on some "
                               "rank since the last setPattern()");
    DMUMPS_STRUC_C& id = handle_->id;
    auto check = [&](const char* phase)
    {
        if (id.infog[0] < 0)
            throw std::runtime_error(std::string("SparseDirectSolver ") + phase +
                                     ": MUMPS INFOG(1) = " + std::to_string(id.infog[0]) +
                                     ", INFOG(2) = " + std::to_string(id.infog[1]) + ": " +
                                     meaning(id.infog[0], id.infog[1]));
    };
    if (global[0] || !analysed_)
    {
        analysed_ = false;
        factorized_ = false;
        const bool metis = options_.ordering == static_cast<int>(Ordering::Metis);
        if (metis)
        {
            const std::vector<int> allRows = gatherOnRoot(rows_, comm_);
            const std::vector<int> allCols = gatherOnRoot(cols_, comm_);
            if (rankOf(comm_) == 0)
                handle_->permutation = metisOrdering(n_, allRows, allCols);
        }
        id.n = n_;
        id.nnz_loc = static_cast<MUMPS_INT8>(rows_.size());
        id.irn_loc = rows_.data();
        id.jcn_loc = cols_.data();
        id.perm_in = metis && rankOf(comm_) == 0 ? handle_->permutation.data() : nullptr;
        id.job = jobAnalyse;
        dmumps_c(&id);
        check("analysis");
        ++analysisCount_;
        analysed_ = true;
        patternChanged_ = false;
    }
    if (global[1] || !factorized_)
    {
        factorized_ = false;
        id.a_loc = values_.data();
        for (int attempt = 0;; ++attempt)
        {
            id.job = jobFactorize;
            dmumps_c(&id);
            if (isWorkspaceError(id.infog[0]) && attempt < 4)
            {
                handle_->icntl(14) = std::max(2 * handle_->icntl(14), 20);
                continue;
            }
            break;
        }
        check("factorization");
        if (handle_->infog(28) > 0)
            throw std::runtime_error(
                "SparseDirectSolver factorization: the matrix is singular (" +
                std::to_string(handle_->infog(28)) +
                " null pivots); check the clamped boundary (rigid-body modes)");
        ++factorizationCount_;
        negativePivots_ = options_.symmetric ? handle_->infog(12) : 0;
        // INFOG(29) < 0 means millions of entries
        factorEntries_ =
            handle_->infog(29) >= 0 ? handle_->infog(29) : -1000000LL * handle_->infog(29);
        factorized_ = true;
        valuesChanged_ = false;
    }
}

void SparseDirectSolver::solve(std::vector<double>& rhsAndSolution)
{
    if (options_.reuseFactorization && options_.symmetric && factorized_ && !refreshFactor_)
    {
        int local[2] = {patternChanged_ ? 1 : 0, valuesChanged_ ? 1 : 0};
        int global[2];
        MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm_);
        if (!global[0] && global[1] && solveWithStaleFactor(rhsAndSolution))
            return;
    }
    refreshFactor_ = false;
    factorize();
    backSubstitute(rhsAndSolution);
    ++solveCount_;
}

void SparseDirectSolver::multiply(std::vector<double>& x, std::vector<double>& y) const
{
    MPI_Bcast(x.data(), n_, MPI_DOUBLE, 0, comm_);
    y.assign(n_, 0.0);
    for (std::size_t k = 0; k < values_.size(); ++k)
    {
        const int i = rows_[k] - 1, j = cols_[k] - 1; // kept triplets are 1-based, lower triangle
        y[i] += values_[k] * x[j];
        if (i != j && options_.symmetric)
            y[j] += values_[k] * x[i];
    }
    if (rankOf(comm_) == 0)
        MPI_Reduce(MPI_IN_PLACE, y.data(), n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
    else
        MPI_Reduce(y.data(), nullptr, n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
}

bool SparseDirectSolver::solveWithStaleFactor(std::vector<double>& b)
{
    const bool root = rankOf(comm_) == 0;
    std::vector<double> x(n_, 0.0), r, z, p(n_, 0.0), q;
    auto dot = [&](const std::vector<double>& u, const std::vector<double>& v) {
        double s = 0.0;
        if (root)
            for (int i = 0; i < n_; ++i)
                s += u[i] * v[i];
        MPI_Bcast(&s, 1, MPI_DOUBLE, 0, comm_);
        return s;
    };
    if (root)
        r = b;
    else
        r.assign(n_, 0.0);
    const double bNorm = std::sqrt(dot(r, r));
    if (!(bNorm > 0.0) || !std::isfinite(bNorm))
        return false;
    z = r;
    backSubstitute(z);
    double rz = dot(r, z);
    if (root)
        p = z;
    for (int it = 1; it <= options_.reuseMaxIterations; ++it)
    {
        multiply(p, q);
        const double pq = dot(p, q);
        if (!(pq > 0.0) || !std::isfinite(pq))
            return false; // indefinite or broken down: factorize instead
        const double alpha = rz / pq;
        if (root)
            for (int i = 0; i < n_; ++i)
            {
                x[i] += alpha * p[i];
                r[i] -= alpha * q[i];
            }
        const double rNorm = std::sqrt(dot(r, r));
        if (rNorm <= options_.reuseTolerance * bNorm)
        {
            if (root)
                b = x;
            ++reusedSolves_;
            reuseIterations_ += it;
            ++solveCount_;
            refreshFactor_ = it > options_.refactorAfterIterations;
            return true;
        }
        z = r;
        backSubstitute(z);
        const double rzNext = dot(r, z);
        const double beta = rzNext / rz;
        rz = rzNext;
        if (root)
            for (int i = 0; i < n_; ++i)
                p[i] = z[i] + beta * p[i];
    }
    return false;
}

void SparseDirectSolver::backSubstitute(std::vector<double>& rhsAndSolution)
{
    DMUMPS_STRUC_C& id = handle_->id;
    int sizeOk = 1;
    if (rankOf(comm_) == 0)
    {
        sizeOk = static_cast<int>(rhsAndSolution.size()) == n_;
        id.rhs = rhsAndSolution.data();
        id.nrhs = 1;
        id.lrhs = n_;
    }
    MPI_Bcast(&sizeOk, 1, MPI_INT, 0, comm_);
    if (!sizeOk)
        throw std::invalid_argument("SparseDirectSolver::solve: rhs size differs from n = " +
                                    std::to_string(n_));
    id.job = jobSolve;
    dmumps_c(&id);
    id.rhs = nullptr;
    if (id.infog[0] < 0)
        throw std::runtime_error(
            "SparseDirectSolver solve: MUMPS INFOG(1) = " + std::to_string(id.infog[0]) + ": " +
            meaning(id.infog[0], id.infog[1]));
}

void SparseDirectSolver::solveSummedRhs(std::vector<double>& rhsAndSolution)
{
    if (static_cast<int>(rhsAndSolution.size()) != n_)
        throw std::invalid_argument("SparseDirectSolver::solveSummedRhs: rhs size differs "
                                    "from n = " +
                                    std::to_string(n_));
    if (rankOf(comm_) == 0)
        MPI_Reduce(MPI_IN_PLACE, rhsAndSolution.data(), n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
    else
        MPI_Reduce(rhsAndSolution.data(), nullptr, n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
    solve(rhsAndSolution);
    broadcastFromRoot(rhsAndSolution);
}

void SparseDirectSolver::broadcastFromRoot(std::vector<double>& vector) const
{
    unsigned long size = vector.size();
    MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, 0, comm_);
    vector.resize(size);
    MPI_Bcast(vector.data(), static_cast<int>(size), MPI_DOUBLE, 0, comm_);
}

} // namespace fsi::linalg
