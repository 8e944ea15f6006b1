// SPDX-License-Identifier: GPL-3.0-or-later
//
// rbf-pu: partition-of-unity RBF for large interfaces; set-up and apply linear in N.
// Patches: along a Morton (Z-order) sweep of the target points, a target not yet within
// centre_spacing * rho of a patch centre becomes the centre c_p of a new patch p, whose points
// are its k nearest source points (k = points_per_patch) and whose radius rho_p is the distance
// to the k-th (times 1 + 1e-6). So every target lies within centre_spacing * rho of some centre,
// and patches follow the local source spacing (graded meshes need no tuning).
// On each patch a local interpolant: polyharmonic cubic phi(r) = r^3 plus the linear polynomial,
// in coordinates centred at c_p and scaled by rho_p, from the small dense saddle-point system
// [Phi Q; Q^T 0] (Q: orthonormal basis of the linear functions the patch points resolve, from
// their principal axes; inverted through the Cholesky factor of P Phi P + Q Q^T, P = I - Q Q^T,
// which is positive definite for distinct points). The patches are blended with Wendland C2 weights
// w_p(x) = psi(|x - c_p| / rho_p), psi(r) = (1 - r)^4_+ (4 r + 1), normalised at each target:
//   H = sum_p diag(w_p / sum_q w_q) L_p        (L_p: Lagrange matrix of patch p, targets x k)
// stored as one sparse matrix (CSR; a row holds the union of its covering patches' points,
// about 2k). Consistent: target = H source. Conservative: source = H^T target (same matrix).
// Every local interpolant reproduces constants and linear functions and the weights sum to 1,
// so H reproduces them exactly: total force and total moment are conserved to round-off.
// A patch whose points are coplanar or collinear resolves fewer linear functions than the
// whole interface (a flat tip cap on a 3-D foil); the targets it covers get the rank-r
// correction  H += D Q^T,  D = Q_t - H Q  (Q, Q_t: global linear basis at sources and targets),
// so linear fields stay exact there too; D is empty when no patch is degenerate.
// A source point in no patch (far from every target) has a zero column: it neither influences
// the targets nor receives force.
// Set-up cost ~ (N_s + N_t) k^2 with a small constant: the local systems are solved when first
// needed and forgotten after their last target (working memory O(sqrt N) patches); memory is
// ~12 bytes per non-zero of H (about 2k per target). Apply: one pass over H, no allocation after
// the first call with a given column count.
#pragma once

#include "mapping/Mapping.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace fsi::mapping
{

namespace detail
{
// Storage of the large arrays of rbf-pu, uninitialised: from 4 MiB on aligned to 2 MiB and, on
// Linux, advised to use transparent huge pages (the set-up writes each page once; with 4 KiB
// pages the page faults cost as much as the arithmetic). Throws std::bad_alloc.
void* allocateLarge(std::size_t bytes);
struct FreeLarge
{
    void operator()(void* p) const;
};
template <class T> using LargeArray = std::unique_ptr<T[], FreeLarge>;
template <class T> LargeArray<T> makeLargeArray(std::size_t n)
{
    return LargeArray<T>(static_cast<T*>(allocateLarge(n * sizeof(T))));
}
} // namespace detail

class RbfPartitionOfUnity;

// Block rbf-pu (optional), partition of unity: local cubic RBF + linear polynomial on
// overlapping patches of k nearest source points, blended by smooth weights. Set-up and apply
// O(N), for any interface size.
struct PartitionOfUnityParameters
{
    static constexpr const char* keyword = "rbf-pu";
    using Strategy = RbfPartitionOfUnity;
    long pointsPerPatch = 20;    // k: source points of each local problem, in [4, 200]; more =
                                 // a little more accurate, cost ~ k^2
    double centreSpacing = 0.85; // in (0, 1): every target lies within this fraction of a patch
                                 // radius from a patch centre; smaller = more overlap, slower
    static const std::vector<std::string>& keys();
    static PartitionOfUnityParameters
    parse(const config::Block& layer); // reads layer.<keyword> (optional)
    void validate() const;
    std::string echo() const;
};

class RbfPartitionOfUnity final : public Mapping
{
public:
    // Pre: params.validate() passes.
    explicit RbfPartitionOfUnity(const PartitionOfUnityParameters& params) : params_(params) {}
    std::string name() const override { return "rbf-pu"; }
    // Throws std::runtime_error on coinciding source points or a singular local system.
    void compute(const PointCloud& source, const PointCloud& target) override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;

    // For the log and the bench.
    Eigen::Index patchCount() const { return patchCount_; }
    Eigen::Index nonZeros() const { return static_cast<Eigen::Index>(nonZeros_); }
    double meanPatchesPerTarget() const { return meanPatchesPerTarget_; }
    Eigen::Index degeneratePatches() const { return degeneratePatches_; }
    Eigen::Index correctedTargets() const { return static_cast<Eigen::Index>(corrected_.size()); }

private:
    PartitionOfUnityParameters params_;
    // H in compressed rows: row t holds value_[i], column_[i] for i in [rowStart_[t],
    // rowStart_[t+1]).
    std::vector<std::int64_t> rowStart_;
    detail::LargeArray<std::int32_t> column_;
    detail::LargeArray<double> value_;
    std::int64_t nonZeros_ = 0;
    // Degenerate-patch correction: D (corrected targets x r) and the source basis Q (N_s x r).
    std::vector<Eigen::Index> corrected_;
    Eigen::MatrixXd correction_, sourceBasis_;
    Eigen::Index patchCount_ = 0, degeneratePatches_ = 0;
    double meanPatchesPerTarget_ = 0.0;
    mutable Eigen::MatrixXd projected_;                            // workspace, r x columns
    mutable Eigen::Matrix<double, 3, Eigen::Dynamic> interleaved_; // workspace, 3 x N_s
};

} // namespace fsi::mapping
