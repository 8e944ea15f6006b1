// SPDX-License-Identifier: GPL-3.0-or-later
// One volume cell: precomputed quadrature data, internal force, consistent tangent, stress.
// Voigt order and shear convention as in material/Material.hpp.
// Kinematics: SmallStrain eps = sym(grad u), stress = Cauchy; TotalLagrangian F = I + Grad u,
// E = (F^T F - I)/2, S = 2nd Piola-Kirchhoff, K = B0^T D B0 + geometric (Grad N_a . S Grad N_b) I.
//
// Volumetric treatment (Formulation, config key solid.element.type):
//   Displacement: the plain element above.
//   ProjectedDilatation: the dilatation the material sees is the L2 projection, per cell, onto
//   a discontinuous space of "dilatation modes" (Hex8: constant, Hex20/Hex27: 1, X, Y, Z):
//     small strain: eps_bar = eps + (theta_bar - tr eps)/3 I, theta = tr eps (B-bar, Hughes
//       1980; with a linear volumetric law (all small-strain laws here) Hex27 with P1 modes is the
//       mixed Q2-P1disc element with its pressure condensed, and Hex8 equals Q1-P0);
//     total Lagrangian: F_bar = (J_bar/J)^(1/3) F, J = det F, E_bar = (F_bar^T F_bar - I)/2
//       (F-bar with a projected J; the internal force is the derivative of the stored energy
//       int W(E_bar) dV, so the tangent is symmetric and consistent).
//   The material law is unchanged: it is evaluated at eps_bar / E_bar. With the dilatation split
//   of the laws (K tr(eps) + deviatoric part) only the volumetric part changes, so the
//   viscoelastic (Prony, deviatoric) law works unchanged. A linear displacement field (constant
//   strain) is reproduced exactly (patch test). Cells without modes (Tet, Prism) stay plain.
#pragma once
#include "material/Material.hpp"
#include "mesh/ReferenceElement.hpp"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fsi::fe
{

enum class Formulation
{
    Displacement,       // plain displacement element (default)
    ProjectedDilatation // B-bar (small strain) / F-bar (total Lagrangian), see above
};

// "displacement" | "projected-dilatation" (the solid.element.type keywords). Throws
// std::invalid_argument for another name.
Formulation formulationFromName(const std::string& name);
const char* formulationName(Formulation formulation);

// Dilatation modes of a cell type: 0 (plain element: Tet, Prism, or Displacement), 1 for Hex8
// (mean dilatation, Q1-P0), 4 for Hex20/Hex27 (P1disc: 1, X, Y, Z in physical coordinates).
int dilatationModeCount(mesh::CellType type, Formulation formulation);

// Names of the cell types among `types` that lock volumetrically at Poisson's ratio nu >= 0.45
// with this formulation: Tet4 and Prism6 always; Hex8, Hex20 (reduced 2x2x2 integration, locks
// partly) and Hex27 (full 3x3x3) with Displacement. Empty below 0.45 or when none lock. Tet10
// and Prism15/Prism18 converge like each other (Cook's membrane at nu = 0.4999, 16 x 16:
// -0.4 %, where the displacement Hex27 is -1.65 % and 12 % short at 4 x 4).
std::vector<std::string> lockingCellTypes(const std::vector<mesh::CellType>& types,
                                          Formulation formulation, double nu);
// Poisson's ratio of the law's isotropic small-strain tangent at zero strain, the larger of
// the instantaneous (dt = 0) and the long-term (dt -> infinity) one (viscoelastic: long-term).
double effectivePoissonRatio(const material::Material& law);

// Flat per-cell quadrature data: per point [w*detJ, N_a (n), dN_a/dX_k (n x 3, column-major)],
// then numModes dilatation mode values per point (numPoints x numModes, point-major).
struct CellQuadrature
{
    int numNodes = 0;
    int numPoints = 0;
    const double* data = nullptr;
    int numModes = 0; // dilatationModeCount(); 0: plain displacement element
    int stride() const { return 1 + 4 * numNodes; }
    double weight(int q) const { return data[q * stride()]; }
    Eigen::Map<const Eigen::VectorXd> N(int q) const { return {data + q * stride() + 1, numNodes}; }
    Eigen::Map<const Eigen::MatrixXd> dNdX(int q) const
    {
        return {data + q * stride() + 1 + numNodes, numNodes, 3};
    }
    // Dilatation mode values at point q (numModes).
    Eigen::Map<const Eigen::VectorXd> modes(int q) const
    {
        return {data + numPoints * stride() + q * numModes, numModes};
    }
};

// Appends the quadrature data of a cell with reference node coordinates X (3 x n) to `out`,
// with numModes dilatation modes per point (0, 1 or 4: dilatationModeCount()). Returns the
// smallest detJ over the points (<= 0: inverted cell; caller decides).
double appendCellQuadrature(mesh::CellType type, const Eigen::Matrix3Xd& X,
                            std::vector<double>& out, int numModes = 0);

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

// What the material sees at each point of a cell: the strain of the kinematics (projected
// dilatation if cq.numModes > 0) and the deformation gradient that pushes its stress forward
// (F, or F_bar; identity in small strain). Use these for history updates and stress output so
// that they match cellResponse(). Throws material::InadmissibleDeformation for J or J_bar <= 0.
struct PointStrain
{
    material::Vector6 strain;
    Eigen::Matrix3d F;
};
std::vector<PointStrain> materialStrains(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                                         material::Kinematics kinematics);

// Internal force fint (3n, node-major: 3a + i) [N] and, if K != nullptr, tangent (3n x 3n)
// of one cell. history: numPoints * historySize doubles (committed), may be nullptr if 0.
// Throws material::InadmissibleDeformation for det F <= 0.
void cellResponse(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                  const material::Material& law, material::Kinematics kinematics,
                  const material::TimeStep& step, const double* history, Eigen::VectorXd& fint,
                  Eigen::MatrixXd* K);

} // namespace fsi::fe
