// SPDX-License-Identifier: GPL-3.0-or-later
// Sparsity of an assembled FE matrix and where each entry lives in the value array.
#pragma once

#include <cstddef>
#include <vector>

namespace fsi::linalg
{

// Compressed rows (0-based), columns sorted within each row. Built from the dof lists of
// the elements this rank assembles; values are then accumulated into a flat array
// values[find(row, col)] and handed to SparseDirectSolver::setValues() together with
// rows()/cols() given once to setPattern().
class CsrPattern
{
public:
    CsrPattern() = default;

    // n: global dof count. elementDofOffsets (size numElements+1) and elementDofs:
    // element e owns elementDofs[elementDofOffsets[e] .. elementDofOffsets[e+1]);
    // negative dofs (constrained) are skipped. lowerOnly: keep row >= col only.
    static CsrPattern fromElements(int n, const std::vector<int>& elementDofOffsets,
                                   const std::vector<int>& elementDofs, bool lowerOnly = false);
    // Same, with one dof list per element.
    static CsrPattern fromElements(int n, const std::vector<std::vector<int>>& elementDofs,
                                   bool lowerOnly = false);

    int size() const { return n_; }
    std::size_t nonZeros() const { return columns_.size(); }
    const std::vector<int>& rowOffsets() const { return rowOffsets_; } // size n+1
    const std::vector<int>& columns() const { return columns_; }

    // Position of (row, col) in the value array, -1 if not in the pattern. O(log row length).
    long find(int row, int col) const;

    // Triplet arrays (CSR order) for SparseDirectSolver::setPattern.
    std::vector<int> tripletRows() const;
    std::vector<int> tripletColumns() const { return columns_; }

private:
    int n_ = 0;
    bool lowerOnly_ = false;
    std::vector<int> rowOffsets_;
    std::vector<int> columns_;
};

} // namespace fsi::linalg
