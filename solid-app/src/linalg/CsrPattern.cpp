// SPDX-License-Identifier: GPL-3.0-or-later
#include "linalg/CsrPattern.hpp"

#include <algorithm>
#include <stdexcept>

namespace fsi::linalg
{

CsrPattern CsrPattern::fromElements(int n, const std::vector<int>& offsets,
                                    const std::vector<int>& dofs, bool lowerOnly)
{
    if (offsets.empty() || offsets.back() != static_cast<int>(dofs.size()))
        throw std::invalid_argument("CsrPattern: element offsets do not match the dof list");
    const int numElements = static_cast<int>(offsets.size()) - 1;

    // dof -> elements incidence (CSR)
    std::vector<int> incidenceOffsets(n + 1, 0);
    for (int d : dofs)
    {
        if (d >= n)
            throw std::invalid_argument("CsrPattern: dof " + std::to_string(d) + " >= n");
        if (d >= 0)
            ++incidenceOffsets[d + 1];
    }
    for (int i = 0; i < n; ++i)
        incidenceOffsets[i + 1] += incidenceOffsets[i];
    std::vector<int> incidence(incidenceOffsets[n]);
    std::vector<int> fill(incidenceOffsets.begin(), incidenceOffsets.end() - 1);
    for (int e = 0; e < numElements; ++e)
        for (int k = offsets[e]; k < offsets[e + 1]; ++k)
            if (dofs[k] >= 0)
                incidence[fill[dofs[k]]++] = e;

    CsrPattern p;
    p.n_ = n;
    p.lowerOnly_ = lowerOnly;
    p.rowOffsets_.assign(n + 1, 0);
    std::vector<int> marker(n, -1);
    for (int row = 0; row < n; ++row)
    {
        const std::size_t begin = p.columns_.size();
        for (int k = incidenceOffsets[row]; k < incidenceOffsets[row + 1]; ++k)
        {
            const int e = incidence[k];
            for (int m = offsets[e]; m < offsets[e + 1]; ++m)
            {
                const int col = dofs[m];
                if (col < 0 || (lowerOnly && col > row) || marker[col] == row)
                    continue;
                marker[col] = row;
                p.columns_.push_back(col);
            }
        }
        std::sort(p.columns_.begin() + begin, p.columns_.end());
        p.rowOffsets_[row + 1] = static_cast<int>(p.columns_.size());
    }
    return p;
}

CsrPattern CsrPattern::fromElements(int n, const std::vector<std::vector<int>>& elementDofs,
                                    bool lowerOnly)
{
    std::vector<int> offsets{0}, dofs;
    for (const auto& element : elementDofs)
    {
        dofs.insert(dofs.end(), element.begin(), element.end());
        offsets.push_back(static_cast<int>(dofs.size()));
    }
    return fromElements(n, offsets, dofs, lowerOnly);
}

long CsrPattern::find(int row, int col) const
{
    if (row < 0 || row >= n_)
        return -1;
    const auto begin = columns_.begin() + rowOffsets_[row];
    const auto end = columns_.begin() + rowOffsets_[row + 1];
    const auto it = std::lower_bound(begin, end, col);
    return (it != end && *it == col) ? static_cast<long>(it - columns_.begin()) : -1;
}

std::vector<int> CsrPattern::tripletRows() const
{
    std::vector<int> rows(columns_.size());
    for (int row = 0; row < n_; ++row)
        std::fill(rows.begin() + rowOffsets_[row], rows.begin() + rowOffsets_[row + 1], row);
    return rows;
}

} // namespace fsi::linalg
