// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfPartitionOfUnity.hpp"

#include "mapping/KdTree.hpp"
#include "mapping/RbfSupport.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

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

int kernelKind()
{
    static const int kind = [] {
        const char* e = std::getenv("FSI_PU_KERNEL");
        return e ? std::atoi(e) : 0;
    }();
    return kind;
}

// Local kernel of squared distance (coordinates scaled by the patch radius).
inline double kernel(double r2)
{
    switch (kernelKind())
    {
    case 1: // thin-plate
        return r2 > 0.0 ? 0.5 * r2 * std::log(r2) : 0.0;
    default: // cubic
        return r2 * std::sqrt(r2);
    }
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
// x^ = (x - c) / rho. Returns the number of linear directions the patch resolves.
class LocalSolver
{
public:
    explicit LocalSolver(int k)
        : k_(k), points_(k, 3), basis_(k, 4), svd_(k, 4, Eigen::ComputeThinU | Eigen::ComputeThinV)
    {
    }

    int solve(const PointCloud& s, const Patches& patches, Eigen::Index p, double duplicate2,
              const PointCloud& source, double* m)
    {
        const int k = k_;
        const double* c = patches.centreOf(p);
        const double rho = patches.radius[static_cast<size_t>(p)];
        const std::int32_t* members = patches.membersOf(p);
        for (int j = 0; j < k; ++j)
            for (int a = 0; a < 3; ++a)
                points_(j, a) = (s(members[j], a) - c[a]) / rho;
        basis_.col(0).setOnes();
        basis_.rightCols(3) = points_;
        svd_.compute(basis_, Eigen::ComputeThinU | Eigen::ComputeThinV);
        const Eigen::VectorXd& sv = svd_.singularValues();
        int r = 0;
        while (r < sv.size() && sv(r) > polynomialDrop * sv(0))
            ++r;

        system_.setZero(k + r, k + r);
        for (int j = 0; j < k; ++j)
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
        system_.topRightCorner(k, r) = svd_.matrixU().leftCols(r);
        system_.bottomLeftCorner(r, k) = svd_.matrixU().leftCols(r).transpose();
        lu_.compute(system_);
        if (!(lu_.rcond() > 1e-13))
            throw std::runtime_error("mapping rbf-pu: local system of the patch at " +
                                     pointText(source, members[0]) +
                                     " is singular; check for near-duplicate source points or "
                                     "raise mapping.rbf-pu.points_per_patch");
        identity_.setIdentity(k + r, k);
        inverse_ = lu_.solve(identity_); // (k + r) x k: A^{-1} restricted to the data columns
        Eigen::Map<Eigen::MatrixXd> out(m, k, k + 4);
        out.leftCols(k) = inverse_.topRows(k);
        // Polynomial part: q(x) = (V_r S_r^{-1})^T [1; x^], so M_poly = Ainv_pk (V_r S_r^{-1})^T.
        transform_ = svd_.matrixV().leftCols(r) * sv.head(r).cwiseInverse().asDiagonal();
        out.rightCols(4).noalias() = inverse_.bottomRows(r).transpose() * transform_.transpose();
        return r;
    }

private:
    int k_;
    Eigen::MatrixXd points_, basis_, system_, identity_, inverse_, transform_;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd_;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

template <int Columns>
void multiplyFixed(const std::vector<std::int64_t>& rowStart, const std::vector<std::int32_t>& column,
                   const std::vector<double>& value, const Eigen::Ref<const Values>& x,
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
        double sum[Columns] = {};
        for (std::int64_t i = rowStart[static_cast<size_t>(t)];
             i < rowStart[static_cast<size_t>(t) + 1]; ++i)
        {
            const double v = value[static_cast<size_t>(i)];
            const std::int32_t j = column[static_cast<size_t>(i)];
            for (int c = 0; c < Columns; ++c)
                sum[c] += v * in[c][j];
        }
        for (int c = 0; c < Columns; ++c)
            out[c][t] = sum[c];
    }
}

template <int Columns>
void multiplyTransposedFixed(const std::vector<std::int64_t>& rowStart,
                             const std::vector<std::int32_t>& column,
                             const std::vector<double>& value, const Eigen::Ref<const Values>& x,
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
            const double v = value[static_cast<size_t>(i)];
            const std::int32_t j = column[static_cast<size_t>(i)];
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
    // 3. Local Lagrange operators.
    const Eigen::Index stride = Eigen::Index(k) * (k + 4);
    std::vector<double> lagrange(static_cast<size_t>(patches.size() * stride));
    std::vector<char> rank(static_cast<size_t>(patches.size()));
    {
        LocalSolver solver(k);
        for (Eigen::Index p = 0; p < patches.size(); ++p)
            rank[static_cast<size_t>(p)] = static_cast<char>(
                solver.solve(s, patches, p, duplicate2, source, lagrange.data() + p * stride));
    }

    PHASE("local")
    // 4. Rows of H: union of the covering patches' points, weights normalised.
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
    column_.assign(static_cast<size_t>(rowStart_.back()), 0);
    value_.assign(static_cast<size_t>(rowStart_.back()), 0.0);
    std::fill(mark.begin(), mark.end(), -1);
    Eigen::VectorXd e(k + 4), lagrangeRow(k);
    for (Eigen::Index i = 0; i < nt; ++i)
    {
        double total = 0.0;
        for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
            total += coverWeight[static_cast<size_t>(c)];
        std::int64_t end = rowStart_[static_cast<size_t>(i)];
        for (std::int64_t c = coverStart[static_cast<size_t>(i)]; c < coverStart[static_cast<size_t>(i) + 1]; ++c)
        {
            const Eigen::Index p = coverPatch[static_cast<size_t>(c)];
            const double* centre = patches.centreOf(p);
            const double rho = patches.radius[static_cast<size_t>(p)];
            const std::int32_t* members = patches.membersOf(p);
            double x[3];
            for (int a = 0; a < 3; ++a)
                x[a] = (t(i, a) - centre[a]) / rho;
            for (int j = 0; j < k; ++j)
            {
                double d2 = 0.0;
                for (int a = 0; a < 3; ++a)
                {
                    const double d = x[a] - (s(members[j], a) - centre[a]) / rho;
                    d2 += d * d;
                }
                e(j) = kernel(d2);
            }
            e(k) = 1.0;
            e(k + 1) = x[0];
            e(k + 2) = x[1];
            e(k + 3) = x[2];
            lagrangeRow.noalias() =
                Eigen::Map<const Eigen::MatrixXd>(lagrange.data() + p * stride, k, k + 4) * e;
            const double w = coverWeight[static_cast<size_t>(c)] / total;
            for (int j = 0; j < k; ++j)
            {
                const size_t g = static_cast<size_t>(members[j]);
                if (mark[g] != i)
                {
                    mark[g] = static_cast<std::int32_t>(i);
                    slot[g] = static_cast<std::int32_t>(end - rowStart_[static_cast<size_t>(i)]);
                    column_[static_cast<size_t>(end)] = members[j];
                    value_[static_cast<size_t>(end)] = w * lagrangeRow(j);
                    ++end;
                }
                else
                    value_[static_cast<size_t>(rowStart_[static_cast<size_t>(i)] + slot[g])] +=
                        w * lagrangeRow(j);
            }
        }
    }

    PHASE("rows")
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
    if (std::getenv("FSI_PU_PROFILE")) std::fprintf(stderr, "  patches %ld per-target %.2f nnz/row %.1f\n", long(patchCount_), meanPatchesPerTarget_, double(column_.size())/nt);
    sourceSize_ = ns;
    targetSize_ = nt;
}

void RbfPartitionOfUnity::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                          Eigen::Ref<Values> targetValues) const
{
    const Eigen::Index columns = sourceValues.cols();
    if (columns == 3)
        multiplyFixed<3>(rowStart_, column_, value_, sourceValues, targetValues);
    else
        for (Eigen::Index c = 0; c < columns; ++c)
            multiplyFixed<1>(rowStart_, column_, value_, sourceValues.col(c), targetValues.col(c));
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
        multiplyTransposedFixed<3>(rowStart_, column_, value_, targetValues, sourceValues);
    else
        for (Eigen::Index c = 0; c < columns; ++c)
            multiplyTransposedFixed<1>(rowStart_, column_, value_, targetValues.col(c),
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
