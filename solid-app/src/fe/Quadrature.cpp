// SPDX-License-Identifier: GPL-3.0-or-later
#include "fe/Quadrature.hpp"

#include <array>
#include <cmath>

namespace fsi::fe
{
namespace
{

using Rule = std::vector<QuadraturePoint>;

Rule gaussLine(int n, std::vector<double>& w)
{
    std::vector<double> x;
    if (n == 2)
    {
        x = {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
        w = {1.0, 1.0};
    }
    else
    {
        x = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
        w = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    }
    Rule r;
    for (std::size_t i = 0; i < x.size(); ++i)
        r.push_back({Eigen::Vector3d(x[i], 0, 0), w[i]});
    return r;
}

Rule tensor(int n, int dim)
{
    std::vector<double> w;
    const Rule line = gaussLine(n, w);
    Rule r;
    for (int k = 0; k < (dim == 3 ? n : 1); ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                r.push_back(
                    {Eigen::Vector3d(line[i].xi[0], line[j].xi[0], dim == 3 ? line[k].xi[0] : 0.0),
                     w[i] * w[j] * (dim == 3 ? w[k] : 1.0)});
    return r;
}

Rule tet(int points)
{
    if (points == 1)
        return {{Eigen::Vector3d(0.25, 0.25, 0.25), 1.0 / 6.0}};
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    return {{Eigen::Vector3d(b, b, b), 1.0 / 24},
            {Eigen::Vector3d(a, b, b), 1.0 / 24},
            {Eigen::Vector3d(b, a, b), 1.0 / 24},
            {Eigen::Vector3d(b, b, a), 1.0 / 24}};
}

Rule tri()
{
    return {{Eigen::Vector3d(1.0 / 6, 1.0 / 6, 0), 1.0 / 6},
            {Eigen::Vector3d(2.0 / 3, 1.0 / 6, 0), 1.0 / 6},
            {Eigen::Vector3d(1.0 / 6, 2.0 / 3, 0), 1.0 / 6}};
}

// 7-point degree-5 rule on the reference triangle (weights sum to 1/2).
Rule tri7()
{
    const double r = std::sqrt(15.0);
    const double a1 = (6 - r) / 21, a2 = (6 + r) / 21, w1 = (155 - r) / 2400, w2 = (155 + r) / 2400;
    return {{Eigen::Vector3d(1.0 / 3, 1.0 / 3, 0), 9.0 / 80},
            {Eigen::Vector3d(a1, a1, 0), w1},
            {Eigen::Vector3d(1 - 2 * a1, a1, 0), w1},
            {Eigen::Vector3d(a1, 1 - 2 * a1, 0), w1},
            {Eigen::Vector3d(a2, a2, 0), w2},
            {Eigen::Vector3d(1 - 2 * a2, a2, 0), w2},
            {Eigen::Vector3d(a2, 1 - 2 * a2, 0), w2}};
}

// triangle rule x Gauss line in w
Rule prism(const Rule& triangle, int linePoints)
{
    std::vector<double> w;
    const Rule line = gaussLine(linePoints, w);
    Rule r;
    for (std::size_t k = 0; k < line.size(); ++k)
        for (const auto& t : triangle)
            r.push_back({Eigen::Vector3d(t.xi[0], t.xi[1], line[k].xi[0]), t.weight * w[k]});
    return r;
}

} // namespace

const std::vector<QuadraturePoint>& quadrature(mesh::CellType type)
{
    using mesh::CellType;
    static const std::array<Rule, mesh::numCellTypes> rules = {
        tet(1),          tet(4),       tensor(2, 3),    tensor(2, 3),
        tensor(3, 3),    tri(),        tri(),           tensor(2, 2),
        tensor(3, 2),    tensor(3, 2), prism(tri(), 2), prism(tri7(), 3),
        prism(tri7(), 3)};
    return rules[static_cast<int>(type)];
}

} // namespace fsi::fe
