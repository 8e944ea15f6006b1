// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/ReferenceElement.hpp"

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

namespace fsi::mesh
{
namespace
{

using V = Eigen::Vector3i;

std::vector<Eigen::Vector3d> points(std::initializer_list<std::array<double, 3>> list)
{
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : list)
        out.emplace_back(p[0], p[1], p[2]);
    return out;
}

std::vector<V> tensorMonomials(int dim, int maxPower)
{
    std::vector<V> m;
    for (int k = 0; k <= (dim == 3 ? maxPower : 0); ++k)
        for (int j = 0; j <= maxPower; ++j)
            for (int i = 0; i <= maxPower; ++i)
                m.emplace_back(i, j, k);
    return m;
}

std::vector<V> completeMonomials(int dim, int degree)
{
    std::vector<V> m;
    for (int k = 0; k <= (dim == 3 ? degree : 0); ++k)
        for (int j = 0; j + k <= degree; ++j)
            for (int i = 0; i + j + k <= degree; ++i)
                m.emplace_back(i, j, k);
    return m;
}

double power(double x, int p)
{
    return p == 0 ? 1.0 : std::pow(x, p);
}
double dpower(double x, int p)
{
    return p == 0 ? 0.0 : p * power(x, p - 1);
}

} // namespace

bool cellTypeFromGmsh(int gmshType, CellType& type)
{
    static const std::map<int, CellType> table = {
        {4, CellType::Tet4},    {11, CellType::Tet10}, {5, CellType::Hex8},
        {17, CellType::Hex20},  {12, CellType::Hex27}, {2, CellType::Tri3},
        {9, CellType::Tri6},    {3, CellType::Quad4},  {16, CellType::Quad8},
        {10, CellType::Quad9},  {6, CellType::Prism6}, {18, CellType::Prism15},
        {13, CellType::Prism18}};
    auto it = table.find(gmshType);
    if (it == table.end())
        return false;
    type = it->second;
    return true;
}

ReferenceElement::ReferenceElement(CellType type) : type_(type)
{
    // Node tables copied from gmsh::model::mesh::getElementProperties (checked by a test).
    const auto hexVertices = {std::array<double, 3>{-1, -1, -1},
                              {1, -1, -1},
                              {1, 1, -1},
                              {-1, 1, -1},
                              {-1, -1, 1},
                              {1, -1, 1},
                              {1, 1, 1},
                              {-1, 1, 1}};
    const auto hexEdges = {std::array<double, 3>{0, -1, -1},
                           {-1, 0, -1},
                           {-1, -1, 0},
                           {1, 0, -1},
                           {1, -1, 0},
                           {0, 1, -1},
                           {1, 1, 0},
                           {-1, 1, 0},
                           {0, -1, 1},
                           {-1, 0, 1},
                           {1, 0, 1},
                           {0, 1, 1}};
    const auto hexFaces = {std::array<double, 3>{0, 0, -1},
                           {0, -1, 0},
                           {-1, 0, 0},
                           {1, 0, 0},
                           {0, 1, 0},
                           {0, 0, 1},
                           {0, 0, 0}};
    auto append = [this](std::initializer_list<std::array<double, 3>> l)
    {
        for (auto& p : points(l))
            nodes_.push_back(p);
    };
    switch (type)
    {
    case CellType::Tet4:
        name_ = "Tet4";
        append({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
        monomials_ = completeMonomials(3, 1);
        break;
    case CellType::Tet10:
        name_ = "Tet10";
        order_ = 2;
        append({{0, 0, 0},
                {1, 0, 0},
                {0, 1, 0},
                {0, 0, 1},
                {.5, 0, 0},
                {.5, .5, 0},
                {0, .5, 0},
                {0, 0, .5},
                {0, .5, .5},
                {.5, 0, .5}});
        monomials_ = completeMonomials(3, 2);
        break;
    case CellType::Hex8:
        name_ = "Hex8";
        simplex_ = false;
        append(hexVertices);
        monomials_ = tensorMonomials(3, 1);
        break;
    case CellType::Hex20:
        name_ = "Hex20";
        simplex_ = false;
        order_ = 2;
        append(hexVertices);
        append(hexEdges);
        // serendipity: all monomials of Q2 except those with two or three squared factors
        for (const V& m : tensorMonomials(3, 2))
        {
            const int squares = (m[0] == 2) + (m[1] == 2) + (m[2] == 2);
            const int degree = m.sum();
            if (squares <= 1 && !(squares == 1 && degree > 4) && degree <= 4)
                monomials_.push_back(m);
        }
        break;
    case CellType::Hex27:
        name_ = "Hex27";
        simplex_ = false;
        order_ = 2;
        append(hexVertices);
        append(hexEdges);
        append(hexFaces);
        monomials_ = tensorMonomials(3, 2);
        break;
    case CellType::Tri3:
        name_ = "Tri3";
        dim_ = 2;
        append({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        monomials_ = completeMonomials(2, 1);
        break;
    case CellType::Tri6:
        name_ = "Tri6";
        dim_ = 2;
        order_ = 2;
        append({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {.5, 0, 0}, {.5, .5, 0}, {0, .5, 0}});
        monomials_ = completeMonomials(2, 2);
        break;
    case CellType::Quad4:
        name_ = "Quad4";
        dim_ = 2;
        simplex_ = false;
        append({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
        monomials_ = tensorMonomials(2, 1);
        break;
    case CellType::Quad8:
    case CellType::Quad9:
        name_ = type == CellType::Quad8 ? "Quad8" : "Quad9";
        dim_ = 2;
        simplex_ = false;
        order_ = 2;
        append({{-1, -1, 0},
                {1, -1, 0},
                {1, 1, 0},
                {-1, 1, 0},
                {0, -1, 0},
                {1, 0, 0},
                {0, 1, 0},
                {-1, 0, 0}});
        if (type == CellType::Quad9)
        {
            append({{0, 0, 0}});
            monomials_ = tensorMonomials(2, 2);
        }
        else
        {
            for (const V& m : tensorMonomials(2, 2))
                if (!(m[0] == 2 && m[1] == 2))
                    monomials_.push_back(m);
        }
        break;
    case CellType::Prism6:
    case CellType::Prism15:
    case CellType::Prism18:
    {
        // triangle (u, v) x line (w in [-1, 1]); Gmsh node table
        simplex_ = false;
        append({{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
        if (type == CellType::Prism6)
        {
            name_ = "Prism6";
            for (const V& m : completeMonomials(2, 1))
                for (int k = 0; k <= 1; ++k)
                    monomials_.emplace_back(m[0], m[1], k);
            break;
        }
        order_ = 2;
        append({{.5, 0, -1},
                {0, .5, -1},
                {0, 0, 0},
                {.5, .5, -1},
                {1, 0, 0},
                {0, 1, 0},
                {.5, 0, 1},
                {0, .5, 1},
                {.5, .5, 1}});
        if (type == CellType::Prism18)
        {
            name_ = "Prism18";
            append({{.5, 0, 0}, {0, .5, 0}, {.5, .5, 0}});
            for (const V& m : completeMonomials(2, 2))
                for (int k = 0; k <= 2; ++k)
                    monomials_.emplace_back(m[0], m[1], k);
        }
        else
        {
            name_ = "Prism15"; // P2(u, v) x {1, w}  +  P1(u, v) x {w^2}
            for (const V& m : completeMonomials(2, 2))
                for (int k = 0; k <= 1; ++k)
                    monomials_.emplace_back(m[0], m[1], k);
            for (const V& m : completeMonomials(2, 1))
                monomials_.emplace_back(m[0], m[1], 2);
        }
        break;
    }
    }
    const int n = numNodes();
    if (static_cast<int>(monomials_.size()) != n)
        throw std::logic_error("ReferenceElement: basis size mismatch for " + name_);
    Eigen::MatrixXd vandermonde(n, n);
    for (int a = 0; a < n; ++a)
        for (int j = 0; j < n; ++j)
            vandermonde(a, j) = power(nodes_[a][0], monomials_[j][0]) *
                                power(nodes_[a][1], monomials_[j][1]) *
                                power(nodes_[a][2], monomials_[j][2]);
    // N_a(x_b) = delta_ab  <=>  V C = I
    coefficients_ = vandermonde.fullPivLu().inverse();
}

const ReferenceElement& ReferenceElement::get(CellType type)
{
    static const std::array<ReferenceElement, numCellTypes> all = {
        ReferenceElement(CellType::Tet4),   ReferenceElement(CellType::Tet10),
        ReferenceElement(CellType::Hex8),   ReferenceElement(CellType::Hex20),
        ReferenceElement(CellType::Hex27),  ReferenceElement(CellType::Tri3),
        ReferenceElement(CellType::Tri6),   ReferenceElement(CellType::Quad4),
        ReferenceElement(CellType::Quad8),  ReferenceElement(CellType::Quad9),
        ReferenceElement(CellType::Prism6), ReferenceElement(CellType::Prism15),
        ReferenceElement(CellType::Prism18)};
    return all[static_cast<int>(type)];
}

void ReferenceElement::evaluate(const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                                Eigen::MatrixXd& dN) const
{
    const int n = numNodes();
    Eigen::VectorXd p(n);
    Eigen::MatrixXd dp(n, dim_);
    for (int j = 0; j < n; ++j)
    {
        const V& m = monomials_[j];
        const double px = power(xi[0], m[0]), py = power(xi[1], m[1]), pz = power(xi[2], m[2]);
        p[j] = px * py * pz;
        dp(j, 0) = dpower(xi[0], m[0]) * py * pz;
        dp(j, 1) = px * dpower(xi[1], m[1]) * pz;
        if (dim_ == 3)
            dp(j, 2) = px * py * dpower(xi[2], m[2]);
    }
    N = coefficients_.transpose() * p;
    dN = coefficients_.transpose() * dp;
}

} // namespace fsi::mesh
