// SPDX-License-Identifier: GPL-3.0-or-later
// Structured test meshes of the unit cube for the linalg tests: m^3 cubes, node (i, j, k)
// numbered i + (m+1) (j + (m+1) k); hexes (8 nodes) or each cube split into 6 tets (4 nodes,
// Kuhn split along the 0-6 diagonal, conforming across cubes).
#pragma once

#include <vector>

namespace fsi::testing
{

inline int cubeNode(int m, int i, int j, int k)
{
    return i + (m + 1) * (j + (m + 1) * k);
}

inline std::vector<std::vector<int>> cubeElements(int m, bool tets)
{
    std::vector<std::vector<int>> elements;
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i)
            {
                const int v[8] = {cubeNode(m, i, j, k),         cubeNode(m, i + 1, j, k),
                                  cubeNode(m, i + 1, j + 1, k), cubeNode(m, i, j + 1, k),
                                  cubeNode(m, i, j, k + 1),     cubeNode(m, i + 1, j, k + 1),
                                  cubeNode(m, i + 1, j + 1, k + 1), cubeNode(m, i, j + 1, k + 1)};
                if (!tets)
                {
                    elements.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
                    continue;
                }
                const int paths[6][2] = {{1, 2}, {1, 5}, {3, 2}, {3, 7}, {4, 5}, {4, 7}};
                for (const auto& p : paths)
                    elements.push_back({v[0], v[p[0]], v[p[1]], v[6]});
            }
    return elements;
}

} // namespace fsi::testing
