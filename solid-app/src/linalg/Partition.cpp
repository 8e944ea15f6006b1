// SPDX-License-Identifier: GPL-3.0-or-later
#include "linalg/Partition.hpp"

#include <metis.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fsi::linalg
{

std::vector<int> partitionElements(int numElements, const std::vector<int>& offsets,
                                   const std::vector<int>& nodes, int numParts, int commonNodes)
{
    if (numParts < 1)
        throw std::invalid_argument("partitionElements: numParts must be >= 1");
    if (static_cast<int>(offsets.size()) != numElements + 1 ||
        offsets.back() != static_cast<int>(nodes.size()))
        throw std::invalid_argument("partitionElements: offsets do not match the connectivity");
    std::vector<int> part(numElements, 0);
    if (numParts == 1 || numElements == 0)
        return part;
    if (numElements <= numParts)
    {
        for (int e = 0; e < numElements; ++e)
            part[e] = e;
        return part;
    }
    idx_t ne = numElements;
    idx_t nn = nodes.empty() ? 0 : *std::max_element(nodes.begin(), nodes.end()) + 1;
    std::vector<idx_t> eptr(offsets.begin(), offsets.end());
    std::vector<idx_t> eind(nodes.begin(), nodes.end());
    idx_t ncommon = commonNodes;
    idx_t nparts = numParts;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    options[METIS_OPTION_SEED] = 1;
    idx_t objval = 0;
    std::vector<idx_t> epart(ne), npart(nn);
    const int status =
        METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                           nullptr, options, &objval, epart.data(), npart.data());
    if (status != METIS_OK)
        throw std::runtime_error("partitionElements: METIS_PartMeshDual failed (status " +
                                 std::to_string(status) + ") for " + std::to_string(numElements) +
                                 " elements into " + std::to_string(numParts) + " parts");
    std::copy(epart.begin(), epart.end(), part.begin());
    return part;
}

std::vector<int> partitionElements(const std::vector<std::vector<int>>& elementNodes, int numParts,
                                   int commonNodes)
{
    std::vector<int> offsets{0}, nodes;
    for (const auto& element : elementNodes)
    {
        nodes.insert(nodes.end(), element.begin(), element.end());
        offsets.push_back(static_cast<int>(nodes.size()));
    }
    return partitionElements(static_cast<int>(elementNodes.size()), offsets, nodes, numParts,
                             commonNodes);
}

} // namespace fsi::linalg
