// SPDX-License-Identifier: GPL-3.0-or-later
//
// QR decomposition with column filtering for the quasi-Newton least-squares problems.
// Columns are taken in the order given (newest first) and orthogonalised by modified
// Gram-Schmidt with one re-orthogonalisation; column j is dropped when its new part is small:
//   Column: |R_jj| < eps |v_j|          (scale-free: a column with < eps of new direction)
//   Matrix: |R_jj| < eps ||V||_F        (= eps ||R||_F, preCICE's QR1 criterion)
// The first (newest) column is kept unless it is zero. Kept columns have V_kept = Q R.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace fsi::acceleration
{

enum class QrFilterKind
{
    Column,
    Matrix
};

struct FilteredQr
{
    Eigen::MatrixXd q;        // n x m_kept, orthonormal columns
    Eigen::MatrixXd r;        // m_kept x m_kept, upper triangular, non-zero diagonal
    std::vector<int> kept;    // indices into the input columns, increasing
    std::vector<int> dropped; // indices into the input columns, increasing
};

FilteredQr filteredQr(const Eigen::MatrixXd& columns, double eps, QrFilterKind kind);

} // namespace fsi::acceleration
