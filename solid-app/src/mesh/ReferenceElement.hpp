// SPDX-License-Identifier: GPL-3.0-or-later
// Reference (parent) elements: node positions in Gmsh's ordering and Lagrange /
// serendipity shape functions built from a monomial basis (V^-1 of the
// Vandermonde matrix), so the node ordering is defined in one table only.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fsi::mesh
{

// Volume cells and boundary faces understood by the solver (Gmsh type ids in comments).
enum class CellType
{
    Tet4,
    Tet10,
    Hex8,
    Hex20,
    Hex27, // 4, 11, 5, 17, 12
    Tri3,
    Tri6,
    Quad4,
    Quad8,
    Quad9, // 2, 9, 3, 16, 10
    Prism6,
    Prism15,
    Prism18
}; // 6, 18, 13
constexpr int numCellTypes = 13;

class ReferenceElement
{
public:
    // The (immutable, shared) reference element of a type.
    static const ReferenceElement& get(CellType type);

    CellType type() const { return type_; }
    const std::string& name() const { return name_; }
    int dim() const { return dim_; }
    int numNodes() const { return static_cast<int>(nodes_.size()); }
    int order() const { return order_; }
    bool isSimplex() const { return simplex_; }
    // Reference coordinates of node a (Gmsh ordering); components beyond dim() are 0.
    const Eigen::Vector3d& node(int a) const { return nodes_[a]; }
    // Shape functions N_a(xi) (size numNodes) and derivatives dN_a/dxi_k (numNodes x dim).
    void evaluate(const Eigen::Vector3d& xi, Eigen::VectorXd& N, Eigen::MatrixXd& dN) const;

private:
    ReferenceElement(CellType type);
    CellType type_;
    std::string name_;
    int dim_ = 3;
    int order_ = 1;
    bool simplex_ = true;
    std::vector<Eigen::Vector3d> nodes_;
    std::vector<Eigen::Vector3i> monomials_; // exponents of the basis
    Eigen::MatrixXd coefficients_;           // N = coefficients_^T p(xi)
};

// Gmsh element type id -> CellType; false if unsupported.
bool cellTypeFromGmsh(int gmshType, CellType& type);

} // namespace fsi::mesh
