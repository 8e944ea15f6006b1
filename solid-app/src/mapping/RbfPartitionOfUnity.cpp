// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfPartitionOfUnity.hpp"
#include "config/YamlReader.hpp"
#include <sstream>

#include "mapping/KdTree.hpp"
#include "mapping/RbfSupport.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

namespace fsi::mapping
{

const std::vector<std::string>& PartitionOfUnityParameters::keys()
{
    static const std::vector<std::string> k{"points_per_patch", "centre_spacing"};
    return k;
}

PartitionOfUnityParameters PartitionOfUnityParameters::parse(const config::Block& layer)
{
    PartitionOfUnityParameters p;
    if (const auto b = layer.optionalBlock(keyword))
    {
        b->allowOnly(keys());
        p.pointsPerPatch = b->integer("points_per_patch", static_cast<int>(p.pointsPerPatch));
        p.centreSpacing = b->number("centre_spacing", p.centreSpacing);
    }
    return p;
}

void PartitionOfUnityParameters::validate() const
{
    if (pointsPerPatch < 4 || pointsPerPatch > 200)
        throw std::runtime_error("mapping.rbf-pu.points_per_patch must be in [4, 200] (got " +
                                 std::to_string(pointsPerPatch) + "); e.g. 20");
    if (!(centreSpacing > 0.0 && centreSpacing < 1.0))
        throw std::runtime_error("mapping.rbf-pu.centre_spacing must be in (0, 1) (got " +
                                 config::formatNumber(centreSpacing) + "); e.g. 0.85");
}

std::string PartitionOfUnityParameters::echo() const
{
    std::ostringstream s;
    s << "{points_per_patch: " << pointsPerPatch << ", centre_spacing: " << centreSpacing << "}";
    return s.str();
}

namespace detail
{
void* allocateLarge(std::size_t bytes)
{
    constexpr std::size_t hugePage = std::size_t(2) << 20;
    void* p = nullptr;
    if (bytes < 2 * hugePage)
        p = std::malloc(std::max<std::size_t>(bytes, 1));
    else
    {
        const std::size_t rounded = (bytes + hugePage - 1) / hugePage * hugePage;
        p = std::aligned_alloc(hugePage, rounded);
#ifdef MADV_HUGEPAGE
        if (p)
            madvise(p, rounded, MADV_HUGEPAGE); // a hint: failure only costs speed
#endif
    }
    if (!p)
        throw std::bad_alloc();
    return p;
}

void FreeLarge::operator()(void* p) const
{
    std::free(p);
}
} // namespace detail

namespace
{
using detail::LargeArray;
using detail::makeLargeArray;

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
std::vector<std::int32_t> mortonOrder(const PointCloud& p)
{
    const Eigen::RowVector3d lo = p.colwise().minCoeff(), hi = p.colwise().maxCoeff();
    const double extent = std::max((hi - lo).maxCoeff(), std::numeric_limits<double>::min());
    const double steps = double((1 << 21) - 1) / extent;
    std::vector<std::pair<std::uint64_t, std::int32_t>> code(static_cast<size_t>(p.rows()));
    for (Eigen::Index i = 0; i < p.rows(); ++i)
    {
        std::uint64_t c = 0;
        for (int a = 0; a < 3; ++a)
            c |= spreadBits(static_cast<std::uint64_t>((p(i, a) - lo(a)) * steps)) << a;
        code[static_cast<size_t>(i)] = {c, static_cast<std::int32_t>(i)};
    }
    std::sort(code.begin(), code.end());
    std::vector<std::int32_t> order(code.size());
    for (size_t i = 0; i < code.size(); ++i)
        order[i] = code[i].second;
    return order;
}

std::string pointText(const PointCloud& points, Eigen::Index i)
{
    char text[96];
    std::snprintf(text, sizeof text, "(%.4g %.4g %.4g) m", points(i, 0), points(i, 1),
                  points(i, 2));
    return text;
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

    // Partition-of-unity weight of patch p at x (3 doubles, m): Wendland C2 of |x - c| / rho,
    // psi(r) = (1 - r)^4 (4 r + 1) for r < 1, else 0.
    double weight(Eigen::Index p, const double* x) const
    {
        const double* c = centreOf(p);
        const double d0 = x[0] - c[0], d1 = x[1] - c[1], d2 = x[2] - c[2];
        const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) / radius[static_cast<size_t>(p)];
        const double a = 1.0 - r;
        return a > 0.0 ? a * a * a * a * (4.0 * r + 1.0) : 0.0;
    }
};

// (target, patch) pairs in chunks of fixed size (no copies while growing).
class CoverPairs
{
public:
    void push(std::int32_t target, std::int32_t patch)
    {
        if (used_ == chunk)
        {
            chunks_.push_back(makeLargeArray<std::int32_t>(2 * chunk));
            used_ = 0;
        }
        chunks_.back()[2 * used_] = target;
        chunks_.back()[2 * used_ + 1] = patch;
        ++used_;
        ++size_;
    }
    std::int64_t size() const { return size_; }
    template <class F> void forEach(F&& f) const
    {
        for (size_t c = 0; c < chunks_.size(); ++c)
        {
            const std::int64_t n = c + 1 < chunks_.size() ? chunk : used_;
            for (std::int64_t i = 0; i < n; ++i)
                f(chunks_[c][2 * i], chunks_[c][2 * i + 1]);
        }
    }

private:
    static constexpr std::int64_t chunk = std::int64_t(1) << 19; // 4 MiB
    std::vector<LargeArray<std::int32_t>> chunks_;
    std::int64_t used_ = chunk, size_ = 0;
};

// Local problem of one patch. Fills M (k x (k + 4), column-major) such that the patch's
// interpolant at x is sum_j L_j(x) f_j with L(x) = M [phi(|x^ - x^_j|); 1; x^],
// x^ = (x - c) / rho, followed by the member coordinates x^_j (3 x k, axis by axis). Returns the
// number of linear functions the patch resolves (1..4). Polynomial basis: the constant and the
// principal axes of the patch points (centroid m, covariance eigenpairs (lambda_i, v_i)), q_i(x) =
// (x^ - m) . v_i / sqrt(lambda_i): orthonormal at the patch points; axes with sqrt(lambda_i) <
// polynomialDrop sqrt(lambda_max) are dropped.
class LocalSolver
{
public:
    explicit LocalSolver(int k) : k_(k), points_(k, 3) {}

    int solve(const PointCloud& source, const Patches& patches, Eigen::Index p, double duplicate2,
              double* m)
    {
        const int k = k_;
        const double* c = patches.centreOf(p);
        const double rho = patches.radius[static_cast<size_t>(p)];
        const std::int32_t* members = patches.membersOf(p);
        const double scale = 1.0 / rho;
        double* local = m + k * (k + 4); // x^ of the members, axis by axis
        for (int j = 0; j < k; ++j)
            for (int a = 0; a < 3; ++a)
                local[a * k + j] = points_(j, a) = (source(members[j], a) - c[a]) * scale;
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

        // Phi and the polynomial basis Q (k x r, orthonormal columns) at the patch points.
        phi_.resize(k, k);
        basis_.resize(k, r);
        for (int j = 0; j < k; ++j)
        {
            phi_(j, j) = 0.0;
            for (int i = 0; i < j; ++i)
            {
                const double d2 = (points_.row(i) - points_.row(j)).squaredNorm();
                if (d2 * rho * rho <= duplicate2)
                    throw std::runtime_error(
                        "mapping rbf-pu: source points " + std::to_string(members[i]) + " and " +
                        std::to_string(members[j]) + " coincide at " +
                        pointText(source, members[i]) +
                        "; merge duplicate wetted nodes or use type nearest-neighbour");
                phi_(i, j) = phi_(j, i) = kernel(d2);
            }
            for (int i = 0; i < r; ++i)
                basis_(j, i) = transform_(0, i) + points_(j, 0) * transform_(1, i) +
                               points_(j, 1) * transform_(2, i) + points_(j, 2) * transform_(3, i);
        }
        // Inverse of the saddle-point matrix [Phi Q; Q^T 0] = [C E; E^T .] with, for P = I - Q Q^T,
        //   C = (P Phi P + Q Q^T)^{-1} - Q Q^T,   E = Q - C Phi Q.
        // P Phi P is positive definite on range(P) (phi = r^3 is conditionally positive definite
        // of order 2), so B = P Phi P + Q Q^T is symmetric positive definite: Cholesky.
        phiBasis_.noalias() = phi_ * basis_; // W = Phi Q
        small_.noalias() = basis_.transpose() * phiBasis_;
        small_.diagonal().array() += 1.0; // S + I, S = Q^T Phi Q
        system_ = phi_;
        system_.noalias() -= basis_ * phiBasis_.transpose();
        system_.noalias() -= phiBasis_ * basis_.transpose();
        product_.noalias() = basis_ * small_;
        system_.noalias() += product_ * basis_.transpose();
        llt_.compute(system_);
        Eigen::Map<Eigen::MatrixXd> out(m, k, k + 4);
        if (llt_.info() == Eigen::Success && !(llt_.rcond() < 1e-13))
        {
            out.leftCols(k).setIdentity();
            llt_.solveInPlace(out.leftCols(k));
            out.leftCols(k).noalias() -= basis_ * basis_.transpose();
        }
        else
            throw std::runtime_error("mapping rbf-pu: local system of the patch at " +
                                     pointText(source, members[0]) +
                                     " is singular; check for near-duplicate source points or "
                                     "raise mapping.rbf-pu.points_per_patch");
        product_ = basis_;
        product_.noalias() -= out.leftCols(k) * phiBasis_; // E = Q - C W
        out.rightCols(4).noalias() = product_ * transform_.leftCols(r).transpose();
        return r;
    }

private:
    int k_;
    Eigen::MatrixXd points_, transform_, phi_, basis_, phiBasis_, small_, product_, system_;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen_;
    Eigen::LLT<Eigen::MatrixXd> llt_;
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
void multiplyTransposedFixed(const std::vector<std::int64_t>& rowStart, const std::int32_t* column,
                             const double* value, const Eigen::Ref<const Values>& x,
                             Eigen::Ref<Values> y)
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
// y = H x for three columns, x interleaved (x_0 y_0 z_0 x_1 ...: a source point's values share
// a cache line, which matters once they no longer fit in the cache).
void multiplyInterleaved(const std::vector<std::int64_t>& rowStart, const std::int32_t* column,
                         const double* value, const double* x, Eigen::Ref<Values> y)
{
    double* out0 = y.col(0).data();
    double* out1 = y.col(1).data();
    double* out2 = y.col(2).data();
    const Eigen::Index rows = static_cast<Eigen::Index>(rowStart.size()) - 1;
    for (Eigen::Index t = 0; t < rows; ++t)
    {
        double sum0 = 0.0, sum1 = 0.0, sum2 = 0.0;
        for (std::int64_t i = rowStart[static_cast<size_t>(t)];
             i < rowStart[static_cast<size_t>(t) + 1]; ++i)
        {
            const double v = value[i];
            const double* xj = x + 3 * std::int64_t(column[i]);
            sum0 += v * xj[0];
            sum1 += v * xj[1];
            sum2 += v * xj[2];
        }
        out0[t] = sum0;
        out1[t] = sum1;
        out2[t] = sum2;
    }
}

// y += H^T x for three columns, y interleaved.
void multiplyTransposedInterleaved(const std::vector<std::int64_t>& rowStart,
                                   const std::int32_t* column, const double* value,
                                   const Eigen::Ref<const Values>& x, double* y)
{
    const double* in0 = x.col(0).data();
    const double* in1 = x.col(1).data();
    const double* in2 = x.col(2).data();
    const Eigen::Index rows = static_cast<Eigen::Index>(rowStart.size()) - 1;
    for (Eigen::Index t = 0; t < rows; ++t)
    {
        const double g0 = in0[t], g1 = in1[t], g2 = in2[t];
        for (std::int64_t i = rowStart[static_cast<size_t>(t)];
             i < rowStart[static_cast<size_t>(t) + 1]; ++i)
        {
            const double v = value[i];
            double* yj = y + 3 * std::int64_t(column[i]);
            yj[0] += v * g0;
            yj[1] += v * g1;
            yj[2] += v * g2;
        }
    }
}
} // namespace

void RbfPartitionOfUnity::compute(const PointCloud& source, const PointCloud& target)
{
    params_.validate();
    const Eigen::Index ns = source.rows(), nt = target.rows();
    if (ns == 0 || nt == 0)
        throw std::runtime_error("mapping rbf-pu: empty interface point cloud (source " +
                                 std::to_string(ns) + " points, target " + std::to_string(nt) +
                                 ")");
    if (ns > std::numeric_limits<std::int32_t>::max() ||
        nt > std::numeric_limits<std::int32_t>::max())
        throw std::runtime_error("mapping rbf-pu: more than 2^31 - 1 interface points");
    const double size = (source.colwise().maxCoeff() - source.colwise().minCoeff()).norm();
    const double duplicate2 = std::pow(1e-12 * size, 2);
    const KdTree sourceTree(source);
    const int k = static_cast<int>(std::min<Eigen::Index>(params_.pointsPerPatch, ns));

    // 1. Patches and cover: along a Morton sweep of the targets, a target not yet within
    // centre_spacing * rho of a patch centre becomes the centre of a new patch (its k nearest
    // source points); every target inside a patch radius is covered by that patch.
    Patches patches;
    patches.k = k;
    std::vector<Eigen::Index> index;
    std::vector<double> distance;
    CoverPairs pairs;
    std::vector<std::int32_t> count(static_cast<size_t>(nt), 0);
    const std::vector<std::int32_t> targetOrder = mortonOrder(target);
    {
        const KdTree targetTree(target);
        std::vector<char> interior(static_cast<size_t>(nt), 0);
        std::vector<std::pair<Eigen::Index, double>> found;
        for (const std::int32_t i : targetOrder)
        {
            if (interior[static_cast<size_t>(i)])
                continue;
            const double* x = target.row(i).data();
            sourceTree.nearest(x, k, index, distance);
            const double rho = 1.000001 * distance.back(); // every member inside
            if (!(rho > 0.0) && k > 1)
                throw std::runtime_error(
                    "mapping rbf-pu: source points " + std::to_string(index[0]) + " and " +
                    std::to_string(index[1]) + " coincide at " + pointText(source, index[0]) +
                    "; merge duplicate wetted nodes or use type "
                    "nearest-neighbour");
            patches.add(x, rho > 0.0 ? rho : 1.0, index); // 1 m: a target on the only source
            const Eigen::Index p = patches.size() - 1;
            const double radius = patches.radius[static_cast<size_t>(p)];
            targetTree.withinRadius(x, radius, found);
            const double inner2 = std::pow(params_.centreSpacing * radius, 2);
            for (const auto& [j, d2] : found)
                if (patches.weight(p, target.row(j).data()) > 0.0)
                {
                    pairs.push(static_cast<std::int32_t>(j), static_cast<std::int32_t>(p));
                    ++count[static_cast<size_t>(j)];
                    if (d2 <= inner2)
                        interior[static_cast<size_t>(j)] = 1;
                }
            interior[static_cast<size_t>(i)] = 1;
        }
    }
    patchCount_ = patches.size();
    meanPatchesPerTarget_ = double(pairs.size()) / double(nt);

    // 2. Target-major cover lists (counting sort) and the number of uses of each patch.
    std::vector<std::int64_t> coverStart(static_cast<size_t>(nt) + 1, 0);
    for (Eigen::Index i = 0; i < nt; ++i)
        coverStart[static_cast<size_t>(i) + 1] =
            coverStart[static_cast<size_t>(i)] + count[static_cast<size_t>(i)];
    LargeArray<std::int32_t> coverPatch = makeLargeArray<std::int32_t>(size_t(pairs.size()));
    {
        std::vector<std::int64_t> next(coverStart.begin(), coverStart.end() - 1);
        pairs.forEach([&](std::int32_t i, std::int32_t p)
                      { coverPatch[static_cast<size_t>(next[static_cast<size_t>(i)]++)] = p; });
        pairs = CoverPairs();
        std::vector<std::int32_t>().swap(count);
    }
    std::vector<std::int32_t> uses(static_cast<size_t>(patches.size()), 0);
    for (std::int64_t c = 0; c < coverStart.back(); ++c)
        ++uses[static_cast<size_t>(coverPatch[c])];

    // 3. Row lengths of H: the union of the covering patches' points.
    std::vector<std::int32_t> mark(static_cast<size_t>(ns), -1), slot(static_cast<size_t>(ns), 0);
    rowStart_.assign(static_cast<size_t>(nt) + 1, 0);
    for (Eigen::Index i = 0; i < nt; ++i)
    {
        std::int64_t n = 0;
        for (std::int64_t c = coverStart[static_cast<size_t>(i)];
             c < coverStart[static_cast<size_t>(i) + 1]; ++c)
        {
            const std::int32_t* members = patches.membersOf(coverPatch[c]);
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
    column_ = makeLargeArray<std::int32_t>(static_cast<size_t>(nonZeros_));
    value_ = makeLargeArray<double>(static_cast<size_t>(nonZeros_));
    std::fill(mark.begin(), mark.end(), -1);

    // 4. Rows of H, targets in Morton order so that the patches they need are recent: each
    // patch's local operator is computed on first use and its block recycled after its last.
    const Eigen::Index stride = Eigen::Index(k) * (k + 7);
    std::vector<std::int32_t> block(static_cast<size_t>(patches.size()), -1);
    std::vector<char> rank(static_cast<size_t>(patches.size()), 4);
    std::vector<double> pool;
    std::vector<std::int32_t> freeBlocks;
    LocalSolver solver(k);
    std::vector<double> e(static_cast<size_t>(k) + 4), lagrangeRow(static_cast<size_t>(k)), weights;
    for (const std::int32_t i : targetOrder)
    {
        const double* x = target.row(i).data();
        const std::int64_t coverBegin = coverStart[static_cast<size_t>(i)];
        const std::int64_t coverEnd = coverStart[static_cast<size_t>(i) + 1];
        weights.resize(static_cast<size_t>(coverEnd - coverBegin));
        double total = 0.0;
        for (std::int64_t c = coverBegin; c < coverEnd; ++c)
            total += weights[static_cast<size_t>(c - coverBegin)] =
                patches.weight(coverPatch[c], x);
        const std::int64_t rowBegin = rowStart_[static_cast<size_t>(i)];
        std::int64_t end = rowBegin;
        for (std::int64_t c = coverBegin; c < coverEnd; ++c)
        {
            const Eigen::Index p = coverPatch[c];
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
                rank[static_cast<size_t>(p)] = static_cast<char>(
                    solver.solve(source, patches, p, duplicate2, pool.data() + b * stride));
            }
            const double* centre = patches.centreOf(p);
            const double scale = 1.0 / patches.radius[static_cast<size_t>(p)];
            const std::int32_t* members = patches.membersOf(p);
            const double* m = pool.data() + b * stride;
            const double* local = m + k * (k + 4);
            const double x0 = (x[0] - centre[0]) * scale, x1 = (x[1] - centre[1]) * scale,
                         x2 = (x[2] - centre[2]) * scale;
            for (int j = 0; j < k; ++j)
            {
                const double d0 = x0 - local[j], d1 = x1 - local[k + j], d2 = x2 - local[2 * k + j];
                e[static_cast<size_t>(j)] = kernel(d0 * d0 + d1 * d1 + d2 * d2);
            }
            e[static_cast<size_t>(k)] = 1.0;
            e[static_cast<size_t>(k) + 1] = x0;
            e[static_cast<size_t>(k) + 2] = x1;
            e[static_cast<size_t>(k) + 3] = x2;
            std::fill(lagrangeRow.begin(), lagrangeRow.end(), 0.0);
            for (int a = 0; a < k + 4; ++a)
            {
                const double ea = e[static_cast<size_t>(a)];
                const double* column = m + a * k;
                for (int j = 0; j < k; ++j)
                    lagrangeRow[static_cast<size_t>(j)] += column[j] * ea;
            }
            if (--uses[static_cast<size_t>(p)] == 0)
                freeBlocks.push_back(b);
            const double w = weights[static_cast<size_t>(c - coverBegin)] / total;
            for (int j = 0; j < k; ++j)
            {
                const size_t g = static_cast<size_t>(members[j]);
                const double v = w * lagrangeRow[static_cast<size_t>(j)];
                if (mark[g] != i)
                {
                    mark[g] = i;
                    slot[g] = static_cast<std::int32_t>(end - rowBegin);
                    column_[end] = members[j];
                    value_[end] = v;
                    ++end;
                }
                else
                    value_[rowBegin + slot[g]] += v;
            }
        }
    }

    // 5. Degenerate patches: correction D = Q_t - H Q on the targets they cover.
    corrected_.clear();
    correction_.resize(0, 0);
    sourceBasis_.resize(0, 0);
    degeneratePatches_ = 0;
    if (*std::min_element(rank.begin(), rank.end()) < 4)
    {
        const detail::Normalisation normalisation(source);
        const detail::LinearPolynomial polynomial(normalisation.apply(source),
                                                  normalisation.apply(target));
        const auto degenerate = [&](Eigen::Index p)
        { return rank[static_cast<size_t>(p)] < polynomial.rank(); };
        for (Eigen::Index p = 0; p < patches.size(); ++p)
            degeneratePatches_ += degenerate(p);
        if (degeneratePatches_ > 0)
        {
            for (Eigen::Index i = 0; i < nt; ++i)
                for (std::int64_t c = coverStart[static_cast<size_t>(i)];
                     c < coverStart[static_cast<size_t>(i) + 1]; ++c)
                    if (degenerate(coverPatch[c]))
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
                for (std::int64_t a = rowStart_[static_cast<size_t>(i)];
                     a < rowStart_[static_cast<size_t>(i) + 1]; ++a)
                    row -= value_[a] * sourceBasis_.row(column_[a]);
                correction_.row(static_cast<Eigen::Index>(n)) = row;
            }
        }
    }
    sourceSize_ = ns;
    targetSize_ = nt;
}

void RbfPartitionOfUnity::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                          Eigen::Ref<Values> targetValues) const
{
    const Eigen::Index columns = sourceValues.cols();
    if (columns == 3)
    {
        if (interleaved_.cols() != sourceSize_)
            interleaved_.resize(3, sourceSize_);
        interleaved_ = sourceValues.transpose();
        multiplyInterleaved(rowStart_, column_.get(), value_.get(), interleaved_.data(),
                            targetValues);
    }
    else
        for (Eigen::Index c = 0; c < columns; ++c)
            multiplyFixed<1>(rowStart_, column_.get(), value_.get(), sourceValues.col(c),
                             targetValues.col(c));
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
    if (columns == 3)
    {
        if (interleaved_.cols() != sourceSize_)
            interleaved_.resize(3, sourceSize_);
        interleaved_.setZero();
        multiplyTransposedInterleaved(rowStart_, column_.get(), value_.get(), targetValues,
                                      interleaved_.data());
        sourceValues = interleaved_.transpose();
    }
    else
        for (Eigen::Index c = 0; c < columns; ++c)
        {
            sourceValues.col(c).setZero();
            multiplyTransposedFixed<1>(rowStart_, column_.get(), value_.get(), targetValues.col(c),
                                       sourceValues.col(c));
        }
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
