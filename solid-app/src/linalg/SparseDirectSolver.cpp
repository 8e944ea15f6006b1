// SPDX-License-Identifier: GPL-3.0-or-later
#include "linalg/SparseDirectSolver.hpp"

#include "fsi/timing/Clock.hpp"

#include <dlfcn.h>
#include <dmumps_c.h>
#include <metis.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#ifdef FSI_MUMPS_HAS_SCOTCH
// Work-around for a MUMPS 5.5 bug that crashes the BLR clustering with SCOTCH 7 (Debian
// bookworm's libmumps-ptscotch): MUMPS_SCOTCH_KWAY_MIXEDto32/64 (ana_orderings_wrappers_m.F)
// call SCOTCHFGRAPHBUILD on a stack array GRAFDAT that was never passed to SCOTCHFGRAPHINIT
// (libmumps_common does not even import scotchfgraphinit_). SCOTCH 7's graph build reads the
// object's context flags first, so the garbage crashed 20 % of the serial and 60 % of the
// 2-rank BLR test runs here (SIGSEGV in SCOTCH_graphBuild). This definition, exported by the
// executable, takes the call: it initializes the graph object, then hands over to SCOTCH's
// own Fortran entry (argument conversions unchanged). MUMPS is the only user of the Fortran
// SCOTCH interface in this process; an extra init of an empty graph is harmless.
extern "C" void scotchfgraphbuild_(double* grafdat, void* baseval, void* vertnbr, void* verttab,
                                   void* vendtab, void* velotab, void* vlbltab, void* edgenbr,
                                   void* edgetab, void* edlotab, int* revaptr)
{
    using Init = void (*)(double*, int*);
    using Build =
        void (*)(double*, void*, void*, void*, void*, void*, void*, void*, void*, void*, int*);
    static const Init init = reinterpret_cast<Init>(dlsym(RTLD_NEXT, "scotchfgraphinit_"));
    static const Build build = reinterpret_cast<Build>(dlsym(RTLD_NEXT, "scotchfgraphbuild_"));
    if (!init || !build)
    {
        *revaptr = 1; // MUMPS ignores the code; SCOTCH missing cannot happen in this build
        return;
    }
    int status = 0;
    init(grafdat, &status);
    build(grafdat, baseval, vertnbr, verttab, vendtab, velotab, vlbltab, edgenbr, edgetab, edlotab,
          revaptr);
}
#endif

// One-column BLAS-3 calls as BLAS-2. MUMPS 5.5's solve phase with one right-hand side calls
// DGEMM (N = 1) for the updates between fronts and DTRSM (one column) for the triangular
// blocks; OpenBLAS 0.3.21 packs the operand blocks of every such call before computing
// (dgemm_itcopy/incopy, dtrsm_*copy), a full extra pass over the factor: 45 % of the solid's
// time in a coupled hydrofoil history (bench/solid-iteration). These definitions, exported by
// the executable (as scotchfgraphbuild_ above), take MUMPS' (and any other library's) calls:
// one column goes to DGEMV / DTRSV (the same products without packing; results differ by
// rounding only), everything else to the BLAS's own entry (dlsym RTLD_NEXT), unchanged.
// Fortran conventions: arguments by reference, then the hidden lengths of the character
// arguments (size_t, gfortran), forwarded as received.
namespace
{
bool isTransposed(const char* op)
{
    return *op == 'T' || *op == 't' || *op == 'C' || *op == 'c';
}
template <class Function> Function nextBlas(const char* name)
{
    return reinterpret_cast<Function>(dlsym(RTLD_NEXT, name));
}
} // namespace

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc, std::size_t transaLength, std::size_t transbLength)
{
    using Gemm = void (*)(const char*, const char*, const int*, const int*, const int*,
                          const double*, const double*, const int*, const double*, const int*,
                          const double*, double*, const int*, std::size_t, std::size_t);
    using Gemv =
        void (*)(const char*, const int*, const int*, const double*, const double*, const int*,
                 const double*, const int*, const double*, double*, const int*, std::size_t);
    static const Gemm gemm = nextBlas<Gemm>("dgemm_");
    static const Gemv gemv = nextBlas<Gemv>("dgemv_");
    if (*n == 1 && *m > 0 && *k > 0 && gemv)
    {
        // C(:, 1) = alpha op(A) op(B)(:, 1) + beta C(:, 1); op(A) is m x k, stored m x k ('N')
        // or k x m ('T'); op(B)(:, 1) is B(:, 1) ('N') or B(1, :) ('T', stride ldb)
        const bool ta = isTransposed(transa);
        const int rows = ta ? *k : *m, columns = ta ? *m : *k;
        const int incx = isTransposed(transb) ? *ldb : 1, incy = 1;
        gemv(ta ? "T" : "N", &rows, &columns, alpha, a, lda, b, &incx, beta, c, &incy, 1);
        return;
    }
    gemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc, transaLength, transbLength);
}

extern "C" void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
                       const int* m, const int* n, const double* alpha, const double* a,
                       const int* lda, double* b, const int* ldb, std::size_t sideLength,
                       std::size_t uploLength, std::size_t transaLength, std::size_t diagLength)
{
    using Trsm = void (*)(const char*, const char*, const char*, const char*, const int*,
                          const int*, const double*, const double*, const int*, double*, const int*,
                          std::size_t, std::size_t, std::size_t, std::size_t);
    using Trsv = void (*)(const char*, const char*, const char*, const int*, const double*,
                          const int*, double*, const int*, std::size_t, std::size_t, std::size_t);
    static const Trsm trsm = nextBlas<Trsm>("dtrsm_");
    static const Trsv trsv = nextBlas<Trsv>("dtrsv_");
    // op(A) X = B with one column and alpha = 1: X = op(A)^-1 B(:, 1)
    if ((*side == 'L' || *side == 'l') && *n == 1 && *m > 0 && *alpha == 1.0 && trsv)
    {
        const int incx = 1;
        trsv(uplo, transa, diag, m, a, lda, b, &incx, uploLength, transaLength, diagLength);
        return;
    }
    trsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb, sideLength, uploLength,
         transaLength, diagLength);
}

namespace fsi::linalg
{

struct SparseDirectSolver::Handle
{
    DMUMPS_STRUC_C id{};
    std::vector<int> permutation; // PERM_IN on rank 0 (1-based positions), METIS ordering
    int& icntl(int i) { return id.icntl[i - 1]; }
    double& cntl(int i) { return id.cntl[i - 1]; }
    int infog(int i) const { return id.infog[i - 1]; }
    double rinfog(int i) const { return id.rinfog[i - 1]; }
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

// METIS nested dissection of the symmetric pattern of the gathered 1-based triplets, on the
// graph compressed to supervariables: consecutive variables with the same closed adjacency
// (the 3 dofs of a node) form one vertex weighted by their count, which cuts METIS' time and
// memory about 9-fold for elasticity. PERM_IN(i) = position of variable i in the pivot order
// (1-based); the variables of a supervariable stay consecutive.
std::vector<int> metisOrdering(int n, const std::vector<int>& rows, const std::vector<int>& cols)
{
    // adjacency without the diagonal, both directions, CSR by counting
    std::vector<long long> start(n + 1, 0);
    for (std::size_t k = 0; k < rows.size(); ++k)
        if (rows[k] != cols[k])
        {
            ++start[rows[k]];
            ++start[cols[k]];
        }
    for (int i = 0; i < n; ++i)
        start[i + 1] += start[i];
    std::vector<int> adjacency(static_cast<std::size_t>(start[n]));
    {
        std::vector<long long> fill(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < rows.size(); ++k)
            if (rows[k] != cols[k])
            {
                adjacency[fill[rows[k] - 1]++] = cols[k] - 1;
                adjacency[fill[cols[k] - 1]++] = rows[k] - 1;
            }
    }
    std::vector<int> degree(n);
    for (int i = 0; i < n; ++i)
    {
        auto first = adjacency.begin() + start[i], last = adjacency.begin() + start[i + 1];
        std::sort(first, last);
        degree[i] = static_cast<int>(std::unique(first, last) - first);
    }
    // closed adjacency of i == that of j (i < j, both in each other's lists)
    auto sameClosed = [&](int i, int j)
    {
        if (degree[i] != degree[j])
            return false;
        const int* a = adjacency.data() + start[i];
        const int* b = adjacency.data() + start[j];
        int p = 0, q = 0;
        while (p < degree[i] || q < degree[j])
        {
            int x = p < degree[i] ? a[p] : n, y = q < degree[j] ? b[q] : n;
            if (x == j) // skip the pair itself
            {
                ++p;
                continue;
            }
            if (y == i)
            {
                ++q;
                continue;
            }
            if (x != y)
                return false;
            ++p;
            ++q;
        }
        return true;
    };
    auto linked = [&](int i, int j)
    {
        return std::binary_search(adjacency.begin() + start[i],
                                  adjacency.begin() + start[i] + degree[i], j);
    };
    std::vector<int> super(n), superStart{0};
    int count = 0;
    for (int i = 0; i < n; ++i)
    {
        if (i > 0 && linked(superStart.back(), i) && sameClosed(superStart.back(), i))
        {
            super[i] = count - 1;
            continue;
        }
        if (i > 0)
            superStart.push_back(i);
        super[i] = count++;
    }
    superStart.push_back(n);
    std::vector<int> permutation(n);
    // quotient graph
    std::vector<idx_t> xadj(count + 1, 0), vwgt(count);
    std::vector<idx_t> adjncy;
    adjncy.reserve(static_cast<std::size_t>(start[n] / 4 + 16));
    std::vector<int> mark(count, -1);
    for (int v = 0; v < count; ++v)
    {
        const int i = superStart[v];
        vwgt[v] = superStart[v + 1] - i;
        mark[v] = v;
        for (long long k = start[i]; k < start[i] + degree[i]; ++k)
        {
            const int w = super[adjacency[k]];
            if (mark[w] != v)
            {
                mark[w] = v;
                adjncy.push_back(w);
            }
        }
        xadj[v + 1] = static_cast<idx_t>(adjncy.size());
    }
    std::vector<int>().swap(adjacency);
    std::vector<idx_t> perm(count), iperm(count);
    if (adjncy.empty())
        std::iota(perm.begin(), perm.end(), 0);
    else
    {
        idx_t nv = count;
        idx_t options[METIS_NOPTIONS];
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_NUMBERING] = 0;
        if (METIS_NodeND(&nv, xadj.data(), adjncy.data(), vwgt.data(), options, perm.data(),
                         iperm.data()) != METIS_OK)
            throw std::runtime_error("SparseDirectSolver: METIS_NodeND ordering failed");
    }
    int position = 1;
    for (int k = 0; k < count; ++k) // perm[k]: the supervariable eliminated k-th
        for (int i = superStart[perm[k]]; i < superStart[perm[k] + 1]; ++i)
            permutation[i] = position++;
    return permutation;
}

// Adds wall and CPU seconds since construction to the two counters.
struct PhaseTimer
{
    double& wall;
    double& cpu;
    double wall0 = timing::wallSeconds(), cpu0 = timing::processCpuSeconds();
    ~PhaseTimer()
    {
        wall += timing::wallSeconds() - wall0;
        cpu += timing::processCpuSeconds() - cpu0;
    }
};

// OpenBLAS / OpenMP thread setters, looked up at run time (no link dependency: Debian's BLAS is
// whatever libblas.so.3 points to).
void setThreads(int threads)
{
    if (threads <= 0)
        return;
    using Setter = void (*)(int);
    for (const char* name : {"openblas_set_num_threads", "omp_set_num_threads"})
        if (void* f = dlsym(RTLD_DEFAULT, name))
            reinterpret_cast<Setter>(f)(threads);
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

bool mumpsHasScotch()
{
#ifdef FSI_MUMPS_HAS_SCOTCH
    return true;
#else
    return false;
#endif
}

bool mumpsHasPtScotch()
{
#ifdef FSI_MUMPS_HAS_PTSCOTCH
    return true;
#else
    return false;
#endif
}

std::optional<DirectSolverOptions::Error> DirectSolverOptions::firstError() const
{
    auto text = [](double v)
    {
        std::ostringstream o;
        o << v;
        return o.str();
    };
    const int o = ordering;
    if (o != 0 && (o < 2 || o > 8))
        return Error{"ordering", std::to_string(o),
                     "use metis (default), scotch, ptscotch, amd, amf, pord, qamd or auto"};
    if (o == static_cast<int>(Ordering::PtScotch) && !mumpsHasPtScotch())
        return Error{"ordering", "ptscotch",
                     "this MUMPS build has no PT-SCOTCH: use metis, or rebuild with "
                     "-DFSI_MUMPS_VARIANT=ptscotch (libmumps-ptscotch-dev)"};
    if (lowRank == LowRank::On && !mumpsHasScotch())
        return Error{"low_rank", "on",
                     "BLR needs MUMPS with SCOTCH (libmumps-ptscotch-dev, then rebuild); use "
                     "off or auto"};
    if (positiveDefinite && !symmetric)
        return Error{"positive_definite", "true", "needs a symmetric matrix"};
    if (memoryRelaxationPercent < 0 || memoryRelaxationPercent > 1000)
        return Error{"memory_relaxation", std::to_string(memoryRelaxationPercent),
                     "give a percentage in [0, 1000] (default 30)"};
    if (verbosity < 0 || verbosity > 4)
        return Error{"verbosity", std::to_string(verbosity), "give 0 (silent) ... 4 (default 0)"};
    if (lowRank != LowRank::Off && lowRank != LowRank::On && lowRank != LowRank::Auto)
        return Error{"low_rank", std::to_string(static_cast<int>(lowRank)),
                     "use auto (default), on or off"};
    if (lowRankMinSize < 1)
        return Error{
            "low_rank_min_size", std::to_string(lowRankMinSize),
            "give the smallest matrix size (rows) for low_rank auto, >= 1 (default 100000)"};
    if (!(lowRankTolerance >= 1e-16 && lowRankTolerance <= 1e-3))
        return Error{"low_rank_tolerance", text(lowRankTolerance),
                     "give the BLR threshold in [1e-16, 1e-3] (default 1e-9)"};
    if (!(refinementTolerance >= 1e-15 && refinementTolerance < 1.0))
        return Error{"refinement_tolerance", text(refinementTolerance),
                     "give |b - A x| / |b| in [1e-15, 1) (default 1e-10)"};
    if (maxRefinementSteps < 0 || maxRefinementSteps > 100)
        return Error{"max_refinement_steps", std::to_string(maxRefinementSteps),
                     "give 0 ... 100 (default 10)"};
    if (threadsPerRank < 0 || threadsPerRank > 1024)
        return Error{"threads", std::to_string(threadsPerRank),
                     "give BLAS threads per MPI rank >= 1 (default 1), or 0 to keep the "
                     "environment's"};
    if (!(reuseTolerance > 0.0 && reuseTolerance < 1.0))
        return Error{"reuse_tolerance", text(reuseTolerance),
                     "give a value in (0, 1) (default 1e-10)"};
    if (reuseMaxIterations < 1)
        return Error{"reuse_max_iterations", std::to_string(reuseMaxIterations),
                     "give >= 1 (default 25)"};
    if (refactorAfterIterations < 0)
        return Error{"refactor_after_iterations", std::to_string(refactorAfterIterations),
                     "give >= 0 (default 12)"};
    return std::nullopt;
}

void DirectSolverOptions::validate() const
{
    if (const auto e = firstError())
        throw std::invalid_argument("linear_solver." + e->key + " = " + e->value +
                                    " is invalid: " + e->fix);
}

std::string describe(const DirectSolverOptions& o)
{
    std::ostringstream s;
    const char* orderings[] = {"amd",   "user", "amf",  "scotch",  "pord",
                               "metis", "qamd", "auto", "ptscotch"};
    s << "ordering " << (o.ordering >= 0 && o.ordering <= 8 ? orderings[o.ordering] : "?")
      << ", low_rank "
      << (o.lowRank == LowRank::On    ? "on"
          : o.lowRank == LowRank::Off ? "off"
                                      : "auto");
    if (o.lowRank != LowRank::Off)
        s << " ("
          << (o.lowRank == LowRank::Auto ? ">= " + std::to_string(o.lowRankMinSize) + " rows, "
                                         : "")
          << "tolerance " << o.lowRankTolerance << ", " << (o.lowRankUcfs ? "ucfs" : "ufsc")
          << "; refinement to " << o.refinementTolerance << " in <= " << o.maxRefinementSteps
          << " steps)";
    s << ", memory_relaxation " << o.memoryRelaxationPercent << " %, threads "
      << (o.threadsPerRank > 0 ? std::to_string(o.threadsPerRank) : "from environment") << ", "
      << (o.positiveDefinite ? "SPD"
          : o.symmetric      ? "symmetric"
                             : "unsymmetric");
    return s.str();
}

std::string blasDescription()
{
    using Config = char* (*)();
    using Threads = int (*)();
    void* config = dlsym(RTLD_DEFAULT, "openblas_get_config");
    if (!config)
        return "reference or other BLAS (not OpenBLAS)";
    std::string text = reinterpret_cast<Config>(config)();
    if (void* threads = dlsym(RTLD_DEFAULT, "openblas_get_num_threads"))
        text += ", " + std::to_string(reinterpret_cast<Threads>(threads)()) + " thread(s)";
    return text;
}

SparseDirectSolver::SparseDirectSolver(MPI_Comm comm, DirectSolverOptions options)
    : handle_(std::make_unique<Handle>()), comm_(comm), options_(options)
{
    options.validate();
    setThreads(options.threadsPerRank);
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
    const bool metis = options.ordering == static_cast<int>(Ordering::Metis);
    const bool parallel = options.ordering == static_cast<int>(Ordering::PtScotch);
    handle_->icntl(28) = parallel ? 2 : 1; // parallel (PT-SCOTCH) or sequential analysis
    handle_->icntl(29) = 1;                // PT-SCOTCH for the parallel analysis
    handle_->icntl(7) = metis ? 1 : parallel ? 7 : options.ordering; // METIS: ours, PERM_IN
    handle_->icntl(14) = options.memoryRelaxationPercent;
    handle_->icntl(22) = 0;   // in-core (no out-of-core factors)
    handle_->icntl(24) = 1;   // null pivot detection: singular -> INFOG(28) > 0
    handle_->cntl(3) = 1e-12; // |pivot row| <= 1e-12 ||A|| counts as null
    handle_->icntl(35) = 0;   // BLR: decided per analysis (analyse())
    handle_->icntl(36) = options.lowRankUcfs ? 1 : 0;
    handle_->cntl(7) = options.lowRankTolerance;
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
    std::vector<double> kept;
    if (keptIndex_.size() == values.size()) // every triplet kept (keptIndex_ is the identity)
        kept = std::move(values);
    else
    {
        kept.resize(keptIndex_.size());
        for (std::size_t k = 0; k < keptIndex_.size(); ++k)
            kept[k] = values[keptIndex_[k]];
    }
    ++valuesVersion_;
    const bool same = valuesSet_ && kept.size() == values_.size() &&
                      std::memcmp(kept.data(), values_.data(), kept.size() * sizeof(double)) == 0;
    valuesSet_ = true;
    if (same)
        return;
    values_ = std::move(kept);
    valuesChanged_ = true;
    matrixNormStale_ = true;
}

namespace
{
void checkInfo(const DMUMPS_STRUC_C& id, const char* phase)
{
    if (id.infog[0] < 0)
        throw std::runtime_error(std::string("SparseDirectSolver ") + phase +
                                 ": MUMPS INFOG(1) = " + std::to_string(id.infog[0]) +
                                 ", INFOG(2) = " + std::to_string(id.infog[1]) + ": " +
                                 meaning(id.infog[0], id.infog[1]));
}
} // namespace

void SparseDirectSolver::factorize()
{
    int local[3] = {patternChanged_ ? 1 : 0, valuesChanged_ ? 1 : 0, valuesSet_ ? 0 : 1};
    int global[3];
    MPI_Allreduce(local, global, 3, MPI_INT, MPI_MAX, comm_);
    if (global[2])
        throw std::logic_error("SparseDirectSolver::factorize: setValues() not called on some "
                               "rank since the last setPattern()");
    if (global[0] || !analysed_)
        analyse();
    if (global[1] || !factorized_)
        factorizeNumerically();
}

void SparseDirectSolver::analyze()
{
    int local = patternChanged_ ? 1 : 0, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, comm_);
    if (global || !analysed_)
        analyse();
}

void SparseDirectSolver::analyse()
{
    PhaseTimer timer{stats_.analysisSeconds, stats_.analysisCpuSeconds};
    DMUMPS_STRUC_C& id = handle_->id;
    analysed_ = false;
    factorized_ = false;
    const bool metis = options_.ordering == static_cast<int>(Ordering::Metis);
    if (metis)
    {
        const double t0 = timing::wallSeconds();
        const std::vector<int> allRows = gatherOnRoot(rows_, comm_);
        const std::vector<int> allCols = gatherOnRoot(cols_, comm_);
        if (rankOf(comm_) == 0)
            handle_->permutation = metisOrdering(n_, allRows, allCols);
        stats_.orderingSeconds += timing::wallSeconds() - t0;
    }
    const bool lowRank = !lowRankDisabled_ && mumpsHasScotch() &&
                         (options_.lowRank == LowRank::On ||
                          (options_.lowRank == LowRank::Auto && n_ >= options_.lowRankMinSize));
    handle_->icntl(35) = lowRank ? 2 : 0;
    id.n = n_;
    id.nnz_loc = static_cast<MUMPS_INT8>(rows_.size());
    id.irn_loc = rows_.data();
    id.jcn_loc = cols_.data();
    id.perm_in = metis && rankOf(comm_) == 0 ? handle_->permutation.data() : nullptr;
    id.job = jobAnalyse;
    dmumps_c(&id);
    checkInfo(id, "analysis");
    ++analysisCount_;
    analysed_ = true;
    patternChanged_ = false;
    stats_.estimatedMemoryMb = handle_->infog(17);
    stats_.fullRankFlops = handle_->rinfog(1); // estimate; the factorization sets RINFOG(3)
}

void SparseDirectSolver::factorizeNumerically()
{
    PhaseTimer timer{stats_.factorizationSeconds, stats_.factorizationCpuSeconds};
    DMUMPS_STRUC_C& id = handle_->id;
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
    checkInfo(id, "factorization");
    if (handle_->infog(28) > 0)
        throw std::runtime_error("SparseDirectSolver factorization: the matrix is singular (" +
                                 std::to_string(handle_->infog(28)) +
                                 " null pivots); check the clamped boundary (rigid-body modes)");
    ++factorizationCount_;
    negativePivots_ = options_.symmetric ? handle_->infog(12) : 0;
    // INFOG(29) < 0 means millions of entries
    factorEntries_ = handle_->infog(29) >= 0 ? handle_->infog(29) : -1000000LL * handle_->infog(29);
    stats_.lowRankActive = handle_->icntl(35) != 0;
    stats_.factorEntries = factorEntries_;
    stats_.lowRankFactorEntries = !stats_.lowRankActive     ? 0
                                  : handle_->infog(35) >= 0 ? handle_->infog(35)
                                                            : -1000000LL * handle_->infog(35);
    stats_.fullRankFlops = handle_->rinfog(3);
    stats_.lowRankFlops = stats_.lowRankActive ? handle_->rinfog(14) : 0.0;
    stats_.maxRankMemoryMb = handle_->infog(18);
    stats_.factorizationMemoryMb = handle_->infog(19);
    factorized_ = true;
    valuesChanged_ = false;
}

bool SparseDirectSolver::cgOnStaleFactor() const
{
    if (!(options_.reuseFactorization && options_.symmetric && factorized_ && !refreshFactor_))
        return false;
    int local[2] = {patternChanged_ ? 1 : 0, valuesChanged_ ? 1 : 0};
    int global[2];
    MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm_);
    return !global[0] && global[1];
}

void SparseDirectSolver::solve(std::vector<double>& rhsAndSolution, double residualAllowance)
{
    if (cgOnStaleFactor() && solveManyWithStaleFactor(rhsAndSolution, 1, {residualAllowance}))
        return;
    refreshFactor_ = false;
    factorize();
    if (!stats_.lowRankActive && !options_.checkResidual)
    {
        backSubstitute(rhsAndSolution);
        ++solveCount_;
        return;
    }
    // BLR factor (approximate), or checkResidual: check the residual and refine; a BLR factor
    // that misses the tolerance is replaced by a full-rank one
    std::vector<double> b;
    if (rankOf(comm_) == 0)
        b = rhsAndSolution;
    backSubstitute(rhsAndSolution);
    if (!refine(b, rhsAndSolution) && stats_.lowRankActive)
    {
        ++stats_.lowRankFallbacks;
        lowRankDisabled_ = true;
        analysed_ = false; // new analysis without BLR
        if (rankOf(comm_) == 0)
            rhsAndSolution = b;
        factorize();
        backSubstitute(rhsAndSolution);
        refine(b, rhsAndSolution); // the full-rank answer is checked too (and in the statistics)
    }
    ++solveCount_;
}

bool SparseDirectSolver::refine(const std::vector<double>& b, std::vector<double>& x)
{
    const bool root = rankOf(comm_) == 0;
    if (matrixNormStale_)
    {
        // ||A||_inf: row sums of |a_ij| (the lower triangle counted for both triangles)
        std::vector<double> rowSums(n_, 0.0);
        for (std::size_t k = 0; k < values_.size(); ++k)
        {
            rowSums[rows_[k] - 1] += std::abs(values_[k]);
            if (options_.symmetric && rows_[k] != cols_[k])
                rowSums[cols_[k] - 1] += std::abs(values_[k]);
        }
        MPI_Allreduce(MPI_IN_PLACE, rowSums.data(), n_, MPI_DOUBLE, MPI_SUM, comm_);
        matrixNorm_ = rowSums.empty() ? 0.0 : *std::max_element(rowSums.begin(), rowSums.end());
        matrixNormStale_ = false;
    }
    std::vector<double> ax, r(root ? n_ : 0);
    double backwardError = 0.0;
    auto residualNorm = [&]()
    {
        PhaseTimer timer{stats_.solveSeconds, stats_.solveCpuSeconds};
        std::vector<double> xs = root ? x : std::vector<double>(n_, 0.0);
        multiply(xs, ax);
        double sums[4] = {0.0, 0.0, 0.0, 0.0}; // |r|^2, |b|^2, |r|_inf, |x|_inf + |b|_inf parts
        if (root)
        {
            double bMax = 0.0, xMax = 0.0;
            for (int i = 0; i < n_; ++i)
            {
                r[i] = b[i] - ax[i];
                sums[0] += r[i] * r[i];
                sums[1] += b[i] * b[i];
                sums[2] = std::max(sums[2], std::abs(r[i]));
                bMax = std::max(bMax, std::abs(b[i]));
                xMax = std::max(xMax, std::abs(x[i]));
            }
            sums[3] = matrixNorm_ * xMax + bMax;
        }
        MPI_Bcast(sums, 4, MPI_DOUBLE, 0, comm_);
        backwardError = sums[3] > 0.0 ? sums[2] / sums[3] : 0.0;
        return sums[1] > 0.0 ? std::sqrt(sums[0] / sums[1]) : std::sqrt(sums[0]);
    };
    // converged: the relative residual meets the tolerance, or the residual is rounding noise
    // (normwise backward error at the level of a backward-stable full-rank solve), which no
    // refinement can lower further
    auto converged = [&](double relative)
    { return relative <= options_.refinementTolerance || backwardError <= kRoundingBackwardError; };
    double relative = residualNorm();
    stats_.lastResiduals.assign(1, relative);
    stats_.lastBackwardErrors.assign(1, backwardError);
    for (int step = 0;
         step < options_.maxRefinementSteps && !converged(relative) && std::isfinite(relative);
         ++step)
    {
        std::vector<double> z = r;
        backSubstitute(z);
        if (root)
            for (int i = 0; i < n_; ++i)
                x[i] += z[i];
        const double next = residualNorm();
        stats_.lastResiduals.push_back(next);
        stats_.lastBackwardErrors.push_back(backwardError);
        ++stats_.refinementSteps;
        const bool stalled = !(next < 0.5 * relative); // BLR too coarse, or at rounding level
        relative = next;
        if (stalled)
            break;
    }
    stats_.lastRelativeResidual = relative;
    stats_.lastBackwardError = backwardError;
    return converged(relative);
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

bool SparseDirectSolver::factorIsStale() const
{
    int local = (!factorized_ || patternChanged_ || valuesChanged_) ? 1 : 0, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, comm_);
    return global != 0;
}

void SparseDirectSolver::multiplyAll(std::vector<double>& x, std::vector<double>& y) const
{
    x.resize(static_cast<std::size_t>(n_));
    multiply(x, y);
    broadcastFromRoot(y);
}

void SparseDirectSolver::backSubstitute(std::vector<double>& rhsAndSolution)
{
    int sizeOk = 1;
    if (rankOf(comm_) == 0)
        sizeOk = static_cast<int>(rhsAndSolution.size()) == n_;
    MPI_Bcast(&sizeOk, 1, MPI_INT, 0, comm_);
    if (!sizeOk)
        throw std::invalid_argument("SparseDirectSolver::solve: rhs size differs from n = " +
                                    std::to_string(n_));
    backSubstitute(rhsAndSolution.data(), 1);
}

void SparseDirectSolver::backSubstitute(double* rhsAndSolutions, int columns)
{
    PhaseTimer timer{stats_.solveSeconds, stats_.solveCpuSeconds};
    DMUMPS_STRUC_C& id = handle_->id;
    if (rankOf(comm_) == 0)
    {
        id.rhs = rhsAndSolutions;
        id.nrhs = columns;
        id.lrhs = n_;
    }
    id.job = jobSolve;
    dmumps_c(&id);
    ++backSubstitutions_;
    id.rhs = nullptr;
    if (id.infog[0] < 0)
        throw std::runtime_error(
            "SparseDirectSolver solve: MUMPS INFOG(1) = " + std::to_string(id.infog[0]) + ": " +
            meaning(id.infog[0], id.infog[1]));
}

void SparseDirectSolver::solveMany(std::vector<double>& rhsAndSolutions, int columns,
                                   const std::vector<double>& residualAllowances)
{
    const bool root = rankOf(comm_) == 0;
    int sizeOk = columns >= 0 && static_cast<int>(residualAllowances.size()) == columns;
    if (root)
        sizeOk = sizeOk && rhsAndSolutions.size() ==
                               static_cast<std::size_t>(n_) * static_cast<std::size_t>(columns);
    MPI_Bcast(&sizeOk, 1, MPI_INT, 0, comm_);
    if (!sizeOk)
        throw std::invalid_argument("SparseDirectSolver::solveMany: expected n x columns rhs "
                                    "values on rank 0 and one allowance per column");
    if (columns == 0)
        return;
    if (cgOnStaleFactor() && solveManyWithStaleFactor(rhsAndSolutions, columns, residualAllowances))
        return;
    refreshFactor_ = false;
    factorize();
    if (stats_.lowRankActive || options_.checkResidual)
    {
        // one by one, each checked and refined (solve() on a current factor)
        std::vector<double> column;
        for (int j = 0; j < columns; ++j)
        {
            if (root)
                column.assign(rhsAndSolutions.begin() + static_cast<std::ptrdiff_t>(j) * n_,
                              rhsAndSolutions.begin() + static_cast<std::ptrdiff_t>(j + 1) * n_);
            solve(column, residualAllowances[j]);
            if (root)
                std::copy(column.begin(), column.end(),
                          rhsAndSolutions.begin() + static_cast<std::ptrdiff_t>(j) * n_);
        }
        return;
    }
    backSubstitute(root ? rhsAndSolutions.data() : nullptr, columns);
    solveCount_ += columns;
}

bool SparseDirectSolver::solveManyWithStaleFactor(std::vector<double>& b, int columns,
                                                  const std::vector<double>& residualAllowances)
{
    // Preconditioned CG on every column, in lockstep: the stale factor is applied to the
    // unfinished columns in one solve phase per iteration.
    const bool root = rankOf(comm_) == 0;
    const std::size_t n = static_cast<std::size_t>(n_);
    const auto col = [n](std::vector<double>& v, int j) { return v.data() + n * j; };
    std::vector<double> x(n * columns, 0.0), r(root ? b : std::vector<double>(n * columns, 0.0));
    std::vector<double> z, p(n * columns, 0.0), q, work(n), product;
    std::vector<double> rz(columns), target(columns);
    std::vector<int> active, iterations(columns, 0);
    auto dotRoot = [&](const double* u, const double* v)
    {
        double sum = 0.0;
        if (root)
            for (std::size_t i = 0; i < n; ++i)
                sum += u[i] * v[i];
        return sum;
    };
    // norms of the rhs (rank 0's, broadcast)
    std::vector<double> norms(columns);
    for (int j = 0; j < columns; ++j)
        norms[j] = std::sqrt(dotRoot(col(r, j), col(r, j)));
    MPI_Bcast(norms.data(), columns, MPI_DOUBLE, 0, comm_);
    for (int j = 0; j < columns; ++j)
    {
        if (!std::isfinite(norms[j]))
            return false;
        target[j] = std::max(options_.reuseTolerance * norms[j], residualAllowances[j]);
        if (norms[j] > residualAllowances[j])
            active.push_back(j); // else x = 0 is within the allowance
    }
    // z = M^-1 r for the active columns, one solve phase
    const auto precondition = [&](const std::vector<int>& which)
    {
        z.assign(n * which.size(), 0.0);
        if (which.empty())
            return; // every column within its allowance: x = 0, no solve phase
        if (root)
            for (std::size_t a = 0; a < which.size(); ++a)
                std::copy(col(r, which[a]), col(r, which[a]) + n, z.data() + n * a);
        backSubstitute(root ? z.data() : nullptr, static_cast<int>(which.size()));
    };
    precondition(active);
    for (std::size_t a = 0; a < active.size(); ++a)
    {
        const int j = active[a];
        if (root)
            std::copy(z.data() + n * a, z.data() + n * (a + 1), col(p, j));
        rz[j] = dotRoot(col(r, j), z.data() + n * a);
    }
    MPI_Bcast(rz.data(), columns, MPI_DOUBLE, 0, comm_);
    int maxIterations = 0;
    for (int it = 1; !active.empty(); ++it)
    {
        if (it > options_.reuseMaxIterations)
            return false;
        std::vector<int> unfinished;
        for (const int j : active)
        {
            std::copy(col(p, j), col(p, j) + n, work.begin());
            multiply(work, product); // broadcasts work from rank 0, product on rank 0
            double pq = dotRoot(col(p, j), product.data());
            MPI_Bcast(&pq, 1, MPI_DOUBLE, 0, comm_);
            if (!(pq > 0.0) || !std::isfinite(pq))
                return false; // indefinite or broken down: factorize instead
            const double alpha = rz[j] / pq;
            if (root)
                for (std::size_t i = 0; i < n; ++i)
                {
                    col(x, j)[i] += alpha * col(p, j)[i];
                    col(r, j)[i] -= alpha * product[i];
                }
            double rNorm = std::sqrt(dotRoot(col(r, j), col(r, j)));
            MPI_Bcast(&rNorm, 1, MPI_DOUBLE, 0, comm_);
            iterations[j] = it;
            if (rNorm > target[j])
                unfinished.push_back(j);
        }
        maxIterations = std::max(maxIterations, it);
        active = unfinished;
        if (active.empty())
            break;
        precondition(active);
        std::vector<double> rzNext(columns, 0.0);
        for (std::size_t a = 0; a < active.size(); ++a)
            rzNext[active[a]] = dotRoot(col(r, active[a]), z.data() + n * a);
        MPI_Bcast(rzNext.data(), columns, MPI_DOUBLE, 0, comm_);
        for (std::size_t a = 0; a < active.size(); ++a)
        {
            const int j = active[a];
            const double beta = rzNext[j] / rz[j];
            rz[j] = rzNext[j];
            if (root)
                for (std::size_t i = 0; i < n; ++i)
                    col(p, j)[i] = z[n * a + i] + beta * col(p, j)[i];
        }
    }
    if (root)
        b = x;
    reusedSolves_ += columns;
    solveCount_ += columns;
    for (const int its : iterations)
        reuseIterations_ += its;
    refreshFactor_ = maxIterations > options_.refactorAfterIterations;
    return true;
}

void SparseDirectSolver::solveSummedRhs(std::vector<double>& rhsAndSolution,
                                        double residualAllowance)
{
    if (static_cast<int>(rhsAndSolution.size()) != n_)
        throw std::invalid_argument("SparseDirectSolver::solveSummedRhs: rhs size differs "
                                    "from n = " +
                                    std::to_string(n_));
    if (rankOf(comm_) == 0)
        MPI_Reduce(MPI_IN_PLACE, rhsAndSolution.data(), n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
    else
        MPI_Reduce(rhsAndSolution.data(), nullptr, n_, MPI_DOUBLE, MPI_SUM, 0, comm_);
    solve(rhsAndSolution, residualAllowance);
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
