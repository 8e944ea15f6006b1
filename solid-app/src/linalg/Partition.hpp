// SPDX-License-Identifier: GPL-3.0-or-later
// METIS element partitioning for distributed assembly.
#pragma once

#include <vector>

namespace fsi::linalg
{

// Part id in [0, numParts) for each element (METIS_PartMeshDual: elements are neighbours
// when they share >= commonNodes nodes; 3 = a triangular face for 3-D solids, also fine
// for quadratic and mixed meshes). Node ids 0-based, any element sizes.
// elementNodeOffsets has numElements+1 entries into elementNodes (CSR, like METIS eptr/eind).
// numParts == 1 or numElements < numParts handled without METIS (round-robin when too few).
// Deterministic (fixed METIS seed). Throws std::runtime_error on METIS failure.
std::vector<int> partitionElements(int numElements, const std::vector<int>& elementNodeOffsets,
                                   const std::vector<int>& elementNodes, int numParts,
                                   int commonNodes = 3);
// Same, with one node list per element (numElements = elementNodes.size()).
std::vector<int> partitionElements(const std::vector<std::vector<int>>& elementNodes, int numParts,
                                   int commonNodes = 3);

} // namespace fsi::linalg
