// SPDX-License-Identifier: GPL-3.0-or-later
// One volume cell: precomputed quadrature data, internal force, consistent tangent, stress.
// Voigt order and shear convention as in material/Material.hpp.
// Kinematics: SmallStrain eps = sym(grad u), stress = Cauchy; TotalLagrangian F = I + Grad u,
// E = (F^T F - I)/2, S = 2nd Piola-Kirchhoff, K = B0^T D B0 + geometric (Grad N_a . S Grad N_b) I.
#pragma once
#include "material/Material.hpp"
#include "mesh/ReferenceElement.hpp"

#include <Eigen/Dense>
#include <vector>

namespace fsi::fe
{

// Flat per-cell quadrature data: per point [w*detJ, N_a (n), dN_a/dX_k (n x 3, column-major)].
struct CellQuadrature
{
    int numNodes = 0;
    int numPoints = 0;
    const double* data = nullptr;
    int stride() const { return 1 + 4 * numNodes; }
    double weight(int q) const { return data[q * stride()]; }
    Eigen::Map<const Eigen::VectorXd> N(int q) const { return {data + q * stride() + 1, numNodes}; }
    Eigen::Map<const Eigen::MatrixXd> dNdX(int q) const
    {
        return {data + q * stride() + 1 + numNodes, numNodes, 3};
    }
};

// Appends the quadrature data of a cell with reference node coordinates X (3 x n) to `out`.
// Returns the smallest detJ over the points (<= 0: inverted cell; caller decides).
double appendCellQuadrature(mesh::CellType type, const Eigen::Matrix3Xd& X,
                            std::vector<double>& out);

// Displacement gradient H = u dNdX at a point; u is 3 x n cell displacements [m].
Eigen::Matrix3d displacementGradient(const CellQuadrature& cq, int q, const Eigen::Matrix3Xd& u);
// Deformation gradient F = I + H.
Eigen::Matrix3d deformationGradient(const CellQuadrature& cq, int q, const Eigen::Matrix3Xd& u);
// Strain measure of the kinematics (engineering shear) from H, never from F: F - I would lose
// the digits of small strains (stiff structures: strains of 1e-9 keep 7 digits only).
//   small strain: sym(H);  total Lagrangian: 0.5 (H + H^T + H^T H) (Green-Lagrange).
material::Vector6 strainFromH(const Eigen::Matrix3d& H, material::Kinematics kinematics);
// Cauchy stress (Voigt, tensor shear) from the material stress of the kinematics.
material::Vector6 cauchyFromMaterialStress(const material::Vector6& stress,
                                           const Eigen::Matrix3d& F,
                                           material::Kinematics kinematics);

// Internal force fint (3n, node-major: 3a + i) [N] and, if K != nullptr, tangent (3n x 3n)
// of one cell. history: numPoints * historySize doubles (committed), may be nullptr if 0.
// Throws material::InadmissibleDeformation for det F <= 0.
void cellResponse(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                  const material::Material& law, material::Kinematics kinematics,
                  const material::TimeStep& step, const double* history, Eigen::VectorXd& fint,
                  Eigen::MatrixXd* K);

} // namespace fsi::fe
