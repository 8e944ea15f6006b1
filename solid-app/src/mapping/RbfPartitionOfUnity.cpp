// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfPartitionOfUnity.hpp"

#include "mapping/KdTree.hpp"
#include "mapping/RbfSupport.hpp"

#include <Eigen/LU>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <ctime>
static double fsiCpu() { timespec ts{}; clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec); }
#define PHASE(name) if (std::getenv("FSI_PU_PROFILE")) { std::fprintf(stderr, "  %-12s %.3f\n", name, fsiCpu() - phase0); } phase0 = fsiCpu();

namespace fsi::mapping
{
namespace
{
// Linear-polynomial directions of a patch with singular value below this fraction of the
// largest are dropped (coplanar or collinear patch points); see the header's correction.
constexpr double polynomialDrop = 1e-4;

// Local kernel, polyharmonic cubic phi(r) = r^3, of the squared distance r^2 (coordinates
// scaled by the patch radius). Conditionally positive definite of order 2: with the linear
// polynomial the local system is non-singular for distinct points.
inline double kernel(double r2)
{
    return r2 * std::sqrt(r2);
}

// Partition-of-unity weight, Wendland C2 of r / rho.
inline double weight(double rOverRho)
{
    const double a = 1.0 - rOverRho;
    return a > 0.0 ? a * a * a * a * (4.0 * rOverRho + 1.0) : 0.0;
}

// 21 bits of v spread to every third bit.
std::uint64_t spreadBits(std::uint64_t v)
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

// Point indices sorted along the Morton (Z-order) curve of their bounding box.
std::vector<Eigen::Index> mortonOrder(const PointCloud& p)
{
    const Eigen::RowVector3d lo = p.colwise().minCoeff(), hi = p.colwise().maxCoeff();
    const double extent = std::max((hi - lo).maxCoeff(), std::numeric_limits<double>::min());
    const double steps = double((1 << 21) - 1) / extent;
    std::vector<std::pair<std::uint64_t, Eigen::Index>> code(static_cast<size_t>(p.rows()));
    for (Eigen::Index i = 0; i < p.rows(); ++i)
    {
        std::uint64_t c = 0;
        for (int a = 0; a < 3; ++a)
            c |= spreadBits(static_cast<std::uint64_t>((p(i, a) - lo(a)) * steps)) << a;
        code[static_cast<size_t>(i)] = {c, i};
    }
    std::sort(code.begin(), code.end());
    std::vector<Eigen::Index> order(code.size());
    for (size_t i = 0; i < code.size(); ++i)
        order[i] = code[i].second;
    return order;
}

// Patches: centre (3), radius and k member indices each, stored flat.
struct Patches
{
    int k = 0;
    std::vector<double> centre, radius;
    std::vector<std::int32_t> member;

    Eigen::Index size() const { return static_cast<Eigen::Index>(radius.size()); }
    void add(const double* c, double rho, const std::vector<Eigen::Index>& members)
    {
        centre.insert(centre.end(), c, c + 3);
        radius.push_back(rho);
        for (int j = 0; j < k; ++j)
            member.push_back(static_cast<std::int32_t>(members[static_cast<size_t>(j)]));
    }
    const double* centreOf(Eigen::Index p) const { return centre.data() + 3 * p; }
    const std::int32_t* membersOf(Eigen::Index p) const { return member.data() + k * p; }
};

// Target-to-patch cover: (target, patch, unnormalised weight).
struct Cover
{
    Eigen::Index target;
    std::int32_t patch;
    double weight;
};

void addCover(const KdTree& targets, const Patches& patches, Eigen::Index p,
              std::vector<std::pair<Eigen::Index, double>>& found, std::vector<Cover>& cover,
              std::vector<std::int32_t>& count)
{
    const double rho = patches.radius[static_cast<size_t>(p)];
    targets.withinRadius(patches.centreOf(p), rho, found);
    for (const auto& [t, d2] : found)
    {
        const double w = weight(std::sqrt(d2) / rho);
        if (w > 0.0)
        {
            cover.push_back({t, static_cast<std::int32_t>(p), w});
            ++count[static_cast<size_t>(t)];
        }
    }
}

std::string pointText(const PointCloud& points, Eigen::Index i)
{
    char text[96];
    std::snprintf(text, sizeof text, "(%.4g %.4g %.4g) m", points(i, 0), points(i, 1),
                  points(i, 2));
    return text;
}

// Local problem of one patch. Fills M (k x (k + 4), column-major) such that the patch's
// interpolant at x is sum_j L_j(x) f_j with L(x) = M [phi(|x^ - x^_j|^2); 1; x^],
// x^ = (x - c) / rho, followed by the member coordinates x^_j (3 x k, axis by axis). Returns the number of linear functions the patch resolves (1..4).
// Polynomial basis: the constant and the principal axes of the patch points (centroid m,
// covariance eigenpairs (lambda_i, v_i)), q_i(x) = (x^ - m) . v_i / sqrt(lambda_i): orthonormal
// at the patch points; axes with sqrt(lambda_i) < polynomialDrop sqrt(lambda_max) are dropped.
class LocalSolver
{
public:
    explicit LocalSolver(int k) : k_(k), points_(k, 3) {}

    int solve(const PointCloud& s, const Patches& patches, Eigen::Index p, double duplicate2,
              const PointCloud& source, double* m)
    {
        const int k = k_;
        const double* c = patches.centreOf(p);
        const double rho = patches.radius[static_cast<size_t>(p)];
        const std::int32_t* members = patches.membersOf(p);
        const double scale = 1.0 / rho;
        double* local = m + k * (k + 4); // x^ of the members, axis by axis
        for (int j = 0; j < k; ++j)
            for (int a = 0; a < 3; ++a)
                local[a * k + j] = points_(j, a) = (s(members[j], a) - c[a]) * scale;
        const Eigen::RowVector3d mean = points_.colwise().mean();
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (int j = 0; j < k; ++j)
        {
            const Eigen::RowVector3d y = points_.row(j) - mean;
            covariance.noalias() += y.transpose() * y;
        }
        eigen_.compute(covariance);
        const Eigen::Vector3d& lambda = eigen_.eigenvalues(); // increasing
        // transform_ (4 x r): q(x) = transform_^T [1; x^].
        transform_.setZero(4, 4);
        transform_(0, 0) = 1.0 / std::sqrt(double(k));
        int r = 1;
        for (int a = 2; a >= 0; --a)
            if (lambda(a) > 0.0 && lambda(a) > polynomialDrop * polynomialDrop * lambda(2))
            {
                const Eigen::Vector3d axis = eigen_.eigenvectors().col(a) / std::sqrt(lambda(a));
                transform_(0, r) = -mean.dot(axis);
                transform_.block<3, 1>(1, r) = axis;
                ++r;
            }

        system_.setZero(k + r, k + r);
        for (int j = 0; j < k; ++j)
        {
            for (int i = 0; i < j; ++i)
            {
                const double d2 = (points_.row(i) - points_.row(j)).squaredNorm();
                if (d2 * rho * rho <= duplicate2)
                    throw std::runtime_error(
                        "mapping rbf-pu: source points " + std::to_string(members[i]) + " and " +
                        std::to_string(members[j]) + " coincide at " +
                        pointText(source, members[i]) +
                        "; merge duplicate wetted nodes or use type nearest-neighbour");
                system_(i, j) = system_(j, i) = kernel(d2);
            }
            system_(j, k) = system_(k, j) = transform_(0, 0);
            for (int i = 1; i < r; ++i)
                system_(j, k + i) = system_(k + i, j) =
                    transform_(0, i) + points_(j, 0) * transform_(1, i) +
                    points_(j, 1) * transform_(2, i) + points_(j, 2) * transform_(3, i);
        }
        lu_.compute(system_);
        if (!(lu_.rcond() > 1e-13))
            throw std::runtime_error("mapping rbf-pu: local system of the patch at " +
                                     pointText(source, members[0]) +
                                     " is singular; check for near-duplicate source points or "
                                     "raise mapping.rbf-pu.points_per_patch");
        identity_.setIdentity(k + r, k);
        inverse_.noalias() = lu_.solve(identity_); // (k + r) x k: A^{-1}, data columns
        Eigen::Map<Eigen::MatrixXd> out(m, k, k + 4);
        out.leftCols(k) = inverse_.topRows(k);
        out.rightCols(4).noalias() =
            inverse_.bottomRows(r).transpose() * transform_.leftCols(r).transpose();
        return r;
    }

private:
    int k_;
    Eigen::MatrixXd points_, system_, identity_, inverse_, transform_;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen_;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

// y = H x (Columns columns at once: one pass over H).
template <int Columns>
void multiplyFixed(const std::vector<std::int64_t>& rowStart, const std::int32_t* column,
                   const double* value, const Eigen::Ref<const Values>& x, Eigen::Ref<Values> y)
{
    const double* in[Columns];
    double* out[Columns];
    for (int c = 0; c < Columns; ++c)
    {
        in[c] = x.col(c).data();
        out[c] = y.col(c).data();
    }
    const Eigen::Index rows = static_cast<Eigen::Index>(rowStart.size()) - 1;
    for (Eigen::Index t = 0; t < rows; ++t)
    {
        double sum[Columns] = {};
        for (std::int64_t i = rowStart[static_cast<size_t>(t)];
             i < rowStart[static_cast<size_t>(t) + 1]; ++i)
        {
            const double v = value[i];
            const std::int32_t j = column[i];
            for (int c = 0; c < Columns; ++c)
                sum[c] += v * in[c][j];
        }
        for (int c = 0; c < Columns; ++c)
            out[c][t] = sum[c];
    }
}

// y += H^T x.
template <int Columns>
void multiplyTransposedFixed(const std::vector<std::int64_t>& rowStart,
                             const std::int32_t* column, const double* value,
                             const Eigen::Ref<const Values>& x, Eigen::Ref<Values> y)
{
    const double* in[Columns];
    double* out[Columns];
    for (int c = 0; c < Columns; ++c)
    {
        in[c] = x.col(c).data();
        out[c] = y.col(c).data();
    }
    const Eigen::Index rows = static_cast<Eigen::Index>(rowStart.size()) - 1;
    for (Eigen::Index t = 0; t < rows; ++t)
    {
        double g[Columns];
        for (int c = 0; c < Columns; ++c)
            g[c] = in[c][t];
        for (std::int64_t i = rowStart[static_cast<size_t>(t)];
             i < rowStart[static_cast<size_t>(t) + 1]; ++i)
        {
            const double v = value[i];
            const std::int32_t j = column[i];
            for (int c = 0; c < Columns; ++c)
                out[c][j] += v * g[c];
        }
    }
}
} // namespace

void RbfPartitionOfUnity::compute(const PointCloud& source, const PointCloud& target)
{
    params_.validate();
    double phase0 = fsiCpu();
    if (source.rows() == 0 || target.rows() == 0)
        throw std::runtime_error("mapping rbf-pu: empty interface point cloud (source " +
                                 std::to_string(source.rows()) + " points, target " +
                                 std::to_string(target.rows()) + ")");
    if (source.rows() > std::numeric_limits<std::int32_t>::max() ||
        target.rows() > std::numeric_limits<std::int32_t>::max())
        throw std::runtime_error("mapping rbf-pu: more than 2^31 interface points");
    const detail::Normalisation normalisation(source);
    const PointCloud s = normalisation.apply(source), t = normalisation.apply(target);
    const Eigen::Index ns = s.rows(), nt = t.rows();
    const double size = (s.colwise().maxCoeff() - s.colwise().minCoeff()).norm();
    const double duplicate2 = std::pow(1e-12 * std::max(size, 1.0), 2);
    const KdTree sourceTree(s);

    PHASE("tree")
    // 1. Patches covering every source point (within centre_spacing * rho of a centre).
    Patches patches;
    patches.k = static_cast<int>(std::min<Eigen::Index>(params_.pointsPerPatch, ns));
    const int k = patches.k;
    std::vector<Eigen::Index> index;
    std::vector<double> distance;
    {
        std::vector<char> covered(static_cast<size_t>(ns), 0);
        for (const Eigen::Index i : mortonOrder(s))
        {
            if (covered[static_cast<size_t>(i)])
                continue;
            sourceTree.nearest(s.row(i).data(), k, index, distance);
            double rho = distance.back();
            if (!(rho > 0.0))
            {
                if (k > 1)
                    throw std::runtime_error("mapping rbf-pu: source points " +
                                             std::to_string(index[0]) + " and " +
                                             std::to_string(index[1]) + " coincide at " +
                                             pointText(source, i) +
                                             "; merge duplicate wetted nodes or use type "
                                             "nearest-neighbour");
                rho = 1.0; // a single source point
            }
            patches.add(s.row(i).data(), rho, index);
            for (int j = 0; j < k; ++j)
                if (distance[static_cast<size_t>(j)] <= params_.centreSpacing * rho)
                    covered[static_cast<size_t>(index[static_cast<size_t>(j)])] = 1;
        }
    }

    PHASE("centres")
    // 2. Targets within each patch radius; a patch of its own for a target in none.
    std::vector<Cover> cover;
    cover.reserve(static_cast<size_t>(nt) * 4);
    std::vector<std::int32_t> count(static_cast<size_t>(nt), 0);
    {
        const KdTree targetTree(t);
        PHASE("target tree")
        std::vector<std::pair<Eigen::Index, double>> found;
        for (Eigen::Index p = 0; p < patches.size(); ++p)
            addCover(targetTree, patches, p, found, cover, count);
        for (Eigen::Index i = 0; i < nt; ++i)
        {
            if (count[static_cast<size_t>(i)] > 0)
                continue;
            sourceTree.nearest(t.row(i).data(), k, index, distance);
            // The target at the centre, its k nearest sources inside the radius.
            const double rho = std::max(1.000001 * distance.back(), 1e-12 * std::max(size, 1.0));
            patches.add(t.row(i).data(), rho, index);
            addCover(targetTree, patches, patches.size() - 1, found, cover, count);
        }
    }
    PHASE("cover")
    patchCount_ = patches.size();
    meanPatchesPerTarget_ = double(cover.size()) / double(nt);

    // Target-major cover lists (counting sort).
    std::vector<std::int64_t> coverStart(static_cast<size_t>(nt) + 1, 0);
    for (Eigen::Index i = 0; i < nt; ++i)
        coverStart[static_cast<size_t>(i) + 1] = coverStart[static_cast<size_t>(i)] + count[static_cast<size_t>(i)];
    std::vector<std::int32_t> coverPatch(cover.size());
    std::vector<double> coverWeight(cover.size());
    {
        std::vector<std::int64_t> next(coverStart.begin(), coverStart.end() - 1);
        for (const Cover& c : cover)
        {
            const std::int64_t at = next[static_cast<size_t>(c.target)]++;
            coverPatch[static_cast<size_t>(at)] = c.patch;
            coverWeight[static_cast<size_t>(at)] = c.weight;
        }
    }
    std::vector<Cover>().swap(cover);
    std::vector<std::int32_t>().swap(count);

    PHASE("sort")
    // 3. Row lengths of H: the union of the covering patches' points.
    std::vector<std::int32_t> mark(static_cast<size_t>(ns), -1), slot(static_cast<size_t>(ns), 0);
    rowStart_.assign(static_cast<size_t>(nt) + 1, 0);
    for (Eigen::Index i = 0; i < nt; ++i)
    {
        std::int64_t n = 0;
        for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
        {
            const std::int32_t* members = patches.membersOf(coverPatch[static_cast<size_t>(c)]);
            for (int j = 0; j < k; ++j)
                if (mark[static_cast<size_t>(members[j])] != i)
                {
                    mark[static_cast<size_t>(members[j])] = static_cast<std::int32_t>(i);
                    ++n;
                }
        }
        rowStart_[static_cast<size_t>(i) + 1] = rowStart_[static_cast<size_t>(i)] + n;
    }
    nonZeros_ = rowStart_.back();
    column_.reset(new std::int32_t[static_cast<size_t>(nonZeros_)]);
    value_.reset(new double[static_cast<size_t>(nonZeros_)]);
    if (std::getenv("PRETOUCH")) { std::fill(value_.get(), value_.get() + nonZeros_, 0.0); std::fill(column_.get(), column_.get() + nonZeros_, 0); }
    PHASE("alloc")
    std::fill(mark.begin(), mark.end(), -1);

    PHASE("count")
    // 4. Rows of H, targets in Morton order so that the patches they need are recent: each
    // patch's Lagrange operator is computed on first use and its block recycled after its last.
    const Eigen::Index stride = Eigen::Index(k) * (k + 7);
    std::vector<std::int32_t> uses(static_cast<size_t>(patches.size()), 0), block(static_cast<size_t>(patches.size()), -1);
    for (const std::int32_t p : coverPatch)
        ++uses[static_cast<size_t>(p)];
    std::vector<char> rank(static_cast<size_t>(patches.size()), 4);
    std::vector<double> pool;
    std::vector<std::int32_t> freeBlocks;
    LocalSolver solver(k);
    std::vector<double> e(static_cast<size_t>(k) + 4), lagrangeRow(static_cast<size_t>(k));
    double solveTime = 0;
    for (const Eigen::Index i : mortonOrder(t))
    {
        double total = 0.0;
        for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
            total += coverWeight[static_cast<size_t>(c)];
        const std::int64_t rowBegin = rowStart_[static_cast<size_t>(i)];
        std::int64_t end = rowBegin;
        for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
        {
            const Eigen::Index p = coverPatch[static_cast<size_t>(c)];
            std::int32_t& b = block[static_cast<size_t>(p)];
            if (b < 0)
            {
                if (freeBlocks.empty())
                {
                    b = static_cast<std::int32_t>(pool.size() / static_cast<size_t>(stride));
                    pool.resize(pool.size() + static_cast<size_t>(stride));
                }
                else
                {
                    b = freeBlocks.back();
                    freeBlocks.pop_back();
                }
                const double q0 = fsiCpu();
                rank[static_cast<size_t>(p)] = static_cast<char>(
                    solver.solve(s, patches, p, duplicate2, source, pool.data() + b * stride));
                solveTime += fsiCpu() - q0;
            }
            const double* centre = patches.centreOf(p);
            const double scale = 1.0 / patches.radius[static_cast<size_t>(p)];
            const std::int32_t* members = patches.membersOf(p);
            const double* m = pool.data() + b * stride;
            const double* local = m + k * (k + 4);
            const double x0 = (t(i, 0) - centre[0]) * scale, x1 = (t(i, 1) - centre[1]) * scale,
                         x2 = (t(i, 2) - centre[2]) * scale;
            for (int j = 0; j < k; ++j)
            {
                const double d0 = x0 - local[j], d1 = x1 - local[k + j], d2 = x2 - local[2 * k + j];
                e[j] = kernel(d0 * d0 + d1 * d1 + d2 * d2);
            }
            e[k] = 1.0;
            e[k + 1] = x0;
            e[k + 2] = x1;
            e[k + 3] = x2;
            std::fill(lagrangeRow.begin(), lagrangeRow.end(), 0.0);
            for (int a = 0; a < k + 4; ++a)
            {
                const double ea = e[a];
                const double* column = m + a * k;
                for (int j = 0; j < k; ++j)
                    lagrangeRow[j] += column[j] * ea;
            }
            if (--uses[static_cast<size_t>(p)] == 0)
                freeBlocks.push_back(b);
            const double w = coverWeight[static_cast<size_t>(c)] / total;
            for (int j = 0; j < k; ++j)
            {
                const size_t g = static_cast<size_t>(members[j]);
                if (mark[g] != i)
                {
                    mark[g] = static_cast<std::int32_t>(i);
                    slot[g] = static_cast<std::int32_t>(end - rowBegin);
                    column_[static_cast<size_t>(end)] = members[j];
                    value_[static_cast<size_t>(end)] = w * lagrangeRow[j];
                    ++end;
                }
                else
                    value_[static_cast<size_t>(rowBegin + slot[g])] += w * lagrangeRow[j];
            }
        }
    }
    PHASE("rows")
    if (std::getenv("FSI_PU_PROFILE")) std::fprintf(stderr, "  solves %.3f\n", solveTime);
    if (std::getenv("FSI_PU_PROFILE")) std::fprintf(stderr, "  pool blocks %zu of %ld patches\n", pool.size() / size_t(stride), long(patches.size()));

    // 5. Degenerate patches: correction D = Q_t - H Q on the targets they cover.
    corrected_.clear();
    correction_.resize(0, 0);
    sourceBasis_.resize(0, 0);
    degeneratePatches_ = 0;
    if (*std::min_element(rank.begin(), rank.end()) < 4)
    {
        const detail::LinearPolynomial polynomial(s, t);
        for (const char r : rank)
            degeneratePatches_ += r < polynomial.rank();
        if (degeneratePatches_ > 0)
        {
            for (Eigen::Index i = 0; i < nt; ++i)
                for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
                    if (rank[static_cast<size_t>(coverPatch[static_cast<size_t>(c)])] < polynomial.rank())
                    {
                        corrected_.push_back(i);
                        break;
                    }
            sourceBasis_ = polynomial.sourceBasis;
            correction_.resize(static_cast<Eigen::Index>(corrected_.size()), polynomial.rank());
            for (size_t n = 0; n < corrected_.size(); ++n)
            {
                const Eigen::Index i = corrected_[n];
                Eigen::RowVectorXd row = polynomial.targetBasis.row(i);
                for (std::int64_t a = rowStart_[static_cast<size_t>(i)]; a < rowStart_[static_cast<size_t>(i) + 1]; ++a)
                    row -= value_[static_cast<size_t>(a)] * sourceBasis_.row(column_[static_cast<size_t>(a)]);
                correction_.row(static_cast<Eigen::Index>(n)) = row;
            }
        }
    }
    PHASE("degenerate")
    if (std::getenv("FSI_PU_PROFILE")) std::fprintf(stderr, "  patches %ld per-target %.2f nnz/row %.1f\n", long(patchCount_), meanPatchesPerTarget_, double(nonZeros_)/nt);
    sourceSize_ = ns;
    targetSize_ = nt;
}

void RbfPartitionOfUnity::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                          Eigen::Ref<Values> targetValues) const
{
    const Eigen::Index columns = sourceValues.cols();
    if (columns == 3)
        multiplyFixed<3>(rowStart_, column_.get(), value_.get(), sourceValues, targetValues);
    else
        for (Eigen::Index c = 0; c < columns; ++c)
            multiplyFixed<1>(rowStart_, column_.get(), value_.get(), sourceValues.col(c), targetValues.col(c));
    if (corrected_.empty())
        return;
    if (projected_.rows() != sourceBasis_.cols() || projected_.cols() != columns)
        projected_.resize(sourceBasis_.cols(), columns);
    for (Eigen::Index c = 0; c < columns; ++c)
        projected_.col(c).noalias() = sourceBasis_.transpose() * sourceValues.col(c);
    for (size_t n = 0; n < corrected_.size(); ++n)
        for (Eigen::Index c = 0; c < columns; ++c)
            targetValues(corrected_[n], c) +=
                correction_.row(static_cast<Eigen::Index>(n)).dot(projected_.col(c));
}

void RbfPartitionOfUnity::applyConservative(const Eigen::Ref<const Values>& targetValues,
                                            Eigen::Ref<Values> sourceValues) const
{
    const Eigen::Index columns = targetValues.cols();
    sourceValues.setZero();
    if (columns == 3)
        multiplyTransposedFixed<3>(rowStart_, column_.get(), value_.get(), targetValues, sourceValues);
    else
        for (Eigen::Index c = 0; c < columns; ++c)
            multiplyTransposedFixed<1>(rowStart_, column_.get(), value_.get(), targetValues.col(c),
                                       sourceValues.col(c));
    if (corrected_.empty())
        return;
    if (projected_.rows() != sourceBasis_.cols() || projected_.cols() != columns)
        projected_.resize(sourceBasis_.cols(), columns);
    projected_.setZero();
    for (size_t n = 0; n < corrected_.size(); ++n)
        for (Eigen::Index c = 0; c < columns; ++c)
            projected_.col(c) += correction_.row(static_cast<Eigen::Index>(n)).transpose() *
                                 targetValues(corrected_[n], c);
    for (Eigen::Index c = 0; c < columns; ++c)
        sourceValues.col(c).noalias() += sourceBasis_ * projected_.col(c);
}

} // namespace fsi::mapping
