// SPDX-License-Identifier: GPL-3.0-or-later
//
// rbf-wendland-c2: compactly supported Wendland C2, phi(r) = (1 - r/rho)^4_+ (4 r/rho + 1),
// positive definite in 3-D, plus the linear polynomial, for large interfaces.
// Polynomial handling: separate least-squares fit, then the RBF on the residual
// (not the saddle-point system, so the sparse matrix stays symmetric positive definite):
//   b = Q^T f            (Q: orthonormal linear basis at the sources, least-squares fit)
//   Phi c = f - Q b      (sparse, SimplicialLDLT with AMD ordering, factorised once)
//   target = Phi_ts c + Q_t b
// i.e. H = Phi_ts Phi^{-1} (I - Q Q^T) + Q_t Q^T, which interpolates the sources and reproduces
// linear fields exactly. Conservative: H^T g = (I - Q Q^T) Phi^{-1} Phi_ts^T g + Q Q_t^T g.
// Every target point needs at least one source point within rho (checked in compute()).
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace fsi::mapping
{

class RbfWendlandC2 final : public Mapping
{
public:
    explicit RbfWendlandC2(double supportRadius) : supportRadius_(supportRadius) {}
    std::string name() const override { return "rbf-wendland-c2"; }
    void compute(const PointCloud& source, const PointCloud& target) override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;

    // Non-zeros of the source matrix Phi and of the evaluation matrix Phi_ts (for the log).
    Eigen::Index systemNonZeros() const { return systemNonZeros_; }
    Eigen::Index evaluationNonZeros() const { return evaluation_.nonZeros(); }

private:
    double supportRadius_; // m
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
    Eigen::SparseMatrix<double, Eigen::RowMajor> evaluation_; // Phi_ts, N_t x N_s
    Eigen::MatrixXd sourceBasis_, targetBasis_;               // Q (N_s x r), Q_t (N_t x r)
    Eigen::Index systemNonZeros_ = 0;
    mutable Eigen::MatrixXd coefficients_, residual_, polynomial_, projected_; // workspace
};

} // namespace fsi::mapping
