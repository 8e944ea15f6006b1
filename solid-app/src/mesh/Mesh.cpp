// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/Mesh.hpp"

#include <limits>
#include <sstream>
#include <stdexcept>

namespace fsi::mesh
{

void CellList::add(CellType type, const int* n, int count)
{
    types.push_back(type);
    connectivity.insert(connectivity.end(), n, n + count);
    offsets.push_back(static_cast<int>(connectivity.size()));
}

const SurfaceGroup& Mesh::surface(const std::string& name) const
{
    auto it = surfaces.find(name);
    if (it == surfaces.end())
        throw std::runtime_error(source + ": no surface physical group '" + name + "'");
    return it->second;
}

std::map<std::string, int> Mesh::cellTypeCounts() const
{
    std::map<std::string, int> counts;
    for (CellType t : cells.types)
        ++counts[ReferenceElement::get(t).name()];
    return counts;
}

double Mesh::minJacobian(int c) const
{
    const ReferenceElement& ref = ReferenceElement::get(cells.types[c]);
    const int* conn = cells.nodes(c);
    const int n = ref.numNodes();
    Eigen::Matrix3Xd x(3, n);
    for (int a = 0; a < n; ++a)
        x.col(a) = nodes.col(conn[a]);
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    double minDet = std::numeric_limits<double>::max();
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int a = 0; a <= n; ++a)
    {
        const Eigen::Vector3d xi = a < n ? ref.node(a) : centroid;
        if (a < n)
            centroid += ref.node(a) / n;
        ref.evaluate(xi, N, dN);
        const Eigen::Matrix3d J = x * dN;
        minDet = std::min(minDet, J.determinant());
    }
    return minDet;
}

void Mesh::checkJacobians() const
{
    for (int c = 0; c < cells.size(); ++c)
    {
        const double det = minJacobian(c);
        if (!(det > 0.0))
        {
            std::ostringstream msg;
            msg << source << ": inverted or degenerate "
                << ReferenceElement::get(cells.types[c]).name() << " cell " << c
                << " (Jacobian determinant " << det
                << " <= 0); fix the node ordering or the geometry";
            throw std::runtime_error(msg.str());
        }
    }
}

int Mesh::nearestNode(const Eigen::Vector3d& x) const
{
    int best = -1;
    double bestDist = std::numeric_limits<double>::max();
    for (int i = 0; i < numNodes(); ++i)
    {
        const double d = (nodes.col(i) - x).squaredNorm();
        if (d < bestDist)
        {
            bestDist = d;
            best = i;
        }
    }
    return best;
}

} // namespace fsi::mesh
