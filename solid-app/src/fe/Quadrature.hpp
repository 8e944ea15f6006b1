// SPDX-License-Identifier: GPL-3.0-or-later
// Gauss rules on the reference cells of mesh::ReferenceElement.
//   Tet4: 1 point (exact for its constant strain). Tet10: 4 points, degree 2 (full: exact
//   stiffness for straight-sided cells). Hex8: 2x2x2. Hex20: 2x2x2 REDUCED (C3D20R: locks
//   only partly for nu -> 0.5, -1.4 % on Cook's membrane at 16 x 16; its single-cell spurious
//   mode does not propagate in meshes of two or more cells). Hex27: 3x3x3 (locks for
//   nu -> 0.5 unless ElementKernel's projected dilatation is used). Faces: Tri3/Tri6 3 points
//   (degree 2), Quad4 2x2, Quad8/Quad9 3x3. Prism6: 3-point triangle x 2-point line;
//   Prism15/Prism18: 7-point (degree 5) triangle x 3-point line.
#pragma once
#include "mesh/ReferenceElement.hpp"

#include <Eigen/Dense>
#include <vector>

namespace fsi::fe
{

struct QuadraturePoint
{
    Eigen::Vector3d xi;
    double weight;
};

const std::vector<QuadraturePoint>& quadrature(mesh::CellType type);

} // namespace fsi::fe
