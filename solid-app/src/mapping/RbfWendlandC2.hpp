// SPDX-License-Identifier: GPL-3.0-or-later
//
// rbf-wendland-c2: compactly supported Wendland C2, phi(r) = (1 - r/rho)^4_+ (4 r/rho + 1),
// positive definite in 3-D, plus the linear polynomial, for large interfaces.
// Polynomial handling: separate least-squares fit, then the RBF on the residual
// (not the saddle-point system, so the sparse matrix stays symmetric positive definite):
//   b = Q^T f            (Q: orthonormal linear basis at the sources, least-squares fit)
//   Phi c = f - Q b      (sparse SPD, factorised once: mumps: MUMPS LDL^T with METIS ordering
//                         (supernodal, BLAS 3; needs MPI initialised); direct: Eigen's
//                         SimplicialLDLT with AMD; iterative: conjugate gradients with
//                         incomplete Cholesky)
//   target = Phi_ts c + Q_t b
// i.e. H = Phi_ts Phi^{-1} (I - Q Q^T) + Q_t Q^T, which interpolates the sources and reproduces
// linear fields exactly. Conservative: H^T g = (I - Q Q^T) Phi^{-1} Phi_ts^T g + Q Q_t^T g.
// Every target point needs at least one source point within rho (checked in compute()).
// Because 1, x, y, z lie in span(Q), (I - Q Q^T) removes them exactly: total force and moment
// are conserved to round-off and linear fields reproduced whatever the accuracy of the solve.
// The Eigen direct and the mumps apply allocate nothing here (MUMPS' own solve workspace aside);
// the iterative one allocates a few work vectors per solve.
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace fsi::mapping
{

class RbfWendlandC2;

// Block rbf-wendland-c2 (required): phi(r) = (1 - r/rho)^4_+ (4 r/rho + 1).
struct WendlandParameters
{
    static constexpr const char* keyword = "rbf-wendland-c2";
    using Strategy = RbfWendlandC2;
    double supportRadius = 0.0; // rho [m]; a few source-node spacings (3..6 is typical)
    // "mumps" (MUMPS LDL^T, METIS ordering: fast set-up and apply; needs MPI initialised) |
    // "direct" (Eigen's simplicial LDLT: no MPI, but its set-up grows fast with N) |
    // "iterative" (CG with incomplete Cholesky, to iterative_tolerance; slow for large supports)
    // | "auto" (mumps when MPI is initialised, as in solid-app; otherwise direct up to
    // direct_max_points source points, iterative above)
    std::string solver = "auto";
    long directMaxPoints = 20000;
    double iterativeTolerance = 1e-10; // relative residual of each CG solve
    static const std::vector<std::string>& keys();
    static WendlandParameters parse(const config::Block& layer); // reads layer.<keyword> (required)
    void validate() const;
    std::string echo() const;
};

class RbfWendlandC2 final : public Mapping
{
public:
    // Pre: params.validate() passes. solver "auto" is resolved in compute() by the source size.
    explicit RbfWendlandC2(const WendlandParameters& params);
    ~RbfWendlandC2() override;
    std::string name() const override { return "rbf-wendland-c2"; }
    void compute(const PointCloud& source, const PointCloud& target) override;
    // Shares this mapping's source system (Phi, its factorisation, the search tree): only the
    // evaluation matrix and the polynomial of the new target are built.
    std::unique_ptr<Mapping> withSameSource(const PointCloud& target) const override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;

    // Non-zeros of the source matrix Phi and of the evaluation matrix Phi_ts (for the log).
    Eigen::Index systemNonZeros() const;
    Eigen::Index evaluationNonZeros() const { return evaluation_.nonZeros(); }
    bool iterative() const;
    // True when both were computed from one source system (withSameSource()).
    bool sharesSourceWith(const RbfWendlandC2& other) const
    {
        return source_ && source_ == other.source_;
    }
    // The solver compute() chose: "mumps", "direct" or "iterative".
    std::string solverInUse() const;
    // CG iterations of the last solve (0 for the direct solver).
    Eigen::Index lastIterations() const { return lastIterations_; }

private:
    // What depends on the source points only (RbfWendlandC2.cpp): shared by the mappings of
    // one source to several targets, so that Phi is factorised once.
    struct SourceSystem;
    enum class Backend
    {
        Mumps,
        Direct,
        Iterative
    };
    // The evaluation matrix Phi_ts and the polynomial at `target` (source_ set). Throws when a
    // target point has no source point within the support radius.
    void computeTarget(const PointCloud& target);
    void solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& solution) const;

    WendlandParameters params_;
    // Shared with the mappings made by withSameSource(); its solvers' state (MUMPS, CG
    // iterations) changes in a const apply, so mappings sharing it serve one thread together.
    std::shared_ptr<SourceSystem> source_;
    // every right-hand side of one apply, column-major (the wrapper's interface: one MUMPS
    // solve phase reads the factor once for all of them), and their (zero) residual allowances
    mutable std::vector<double> mumpsColumns_;
    mutable std::vector<double> mumpsAllowances_;
    mutable Eigen::Index lastIterations_ = 0;
    Eigen::SparseMatrix<double, Eigen::RowMajor> evaluation_; // Phi_ts, N_t x N_s
    Eigen::MatrixXd sourceBasis_, targetBasis_;               // Q (N_s x r), Q_t (N_t x r)
    mutable Eigen::MatrixXd coefficients_, residual_, polynomial_, projected_,
        permuted_; // workspace
};

} // namespace fsi::mapping
