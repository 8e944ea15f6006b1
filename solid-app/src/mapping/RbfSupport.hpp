// SPDX-License-Identifier: GPL-3.0-or-later
//
// Pieces shared by the RBF mappings: coordinate normalisation and the linear polynomial basis.
#pragma once

#include "mapping/Mapping.hpp"

namespace fsi::mapping::detail
{

// x_hat = (x - centre) / scale, with centre and scale (longest side) of the source bounding
// box, so that the source lies in [-0.5, 0.5]^3: RBF conditioning no longer depends on units.
struct Normalisation
{
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    double scale = 1.0; // m
    explicit Normalisation(const PointCloud& source);
    PointCloud apply(const PointCloud& points) const;
};

// Linear polynomial space {1, x, y, z} restricted to what the source cloud can resolve.
// With P_s = [1 x y z] at the (normalised) source points and its thin SVD P_s = U S V^T, the
// directions with s_i < 1e-6 s_max are dropped (e.g. a flat interface has no z-dependence):
//   sourceBasis = U_r (N_s x r, orthonormal columns)
//   targetBasis = P_t V_r S_r^{-1} (N_t x r): the same r linear functions at the targets.
// A linear field f = P_s a (a in span V_r) has sourceBasis^T f coefficients b and is
// reproduced at the targets as targetBasis b.
struct LinearPolynomial
{
    Eigen::MatrixXd sourceBasis;
    Eigen::MatrixXd targetBasis;
    LinearPolynomial(const PointCloud& sourceNormalised, const PointCloud& targetNormalised);
    Eigen::Index rank() const { return sourceBasis.cols(); }
};

// Throws when two source points coincide (the RBF system would be singular).
void checkDistinctPoints(const PointCloud& source, const char* mappingName);

} // namespace fsi::mapping::detail
