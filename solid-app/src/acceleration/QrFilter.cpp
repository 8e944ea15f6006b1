// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/QrFilter.hpp"

namespace fsi::acceleration
{

FilteredQr filteredQr(const Eigen::MatrixXd& columns, double eps, QrFilterKind kind)
{
    const Eigen::Index n = columns.rows(), m = columns.cols();
    FilteredQr out;
    out.q.resize(n, m);
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(m, m); // rows: kept, cols: input index
    const double matrixNorm = columns.norm();
    Eigen::Index k = 0; // kept so far
    for (Eigen::Index j = 0; j < m; ++j)
    {
        Eigen::VectorXd v = columns.col(j);
        const double columnNorm = v.norm();
        Eigen::VectorXd coefficients = Eigen::VectorXd::Zero(k);
        for (int pass = 0; pass < 2; ++pass) // MGS twice: orthogonal to round-off
            for (Eigen::Index i = 0; i < k; ++i)
            {
                const double c = out.q.col(i).dot(v);
                coefficients(i) += c;
                v -= c * out.q.col(i);
            }
        const double diagonal = v.norm();
        const double limit = eps * (kind == QrFilterKind::Column ? columnNorm : matrixNorm);
        const bool keep = diagonal > 0.0 && (k == 0 || diagonal >= limit);
        if (!keep)
        {
            out.dropped.push_back(static_cast<int>(j));
            continue;
        }
        out.q.col(k) = v / diagonal;
        r.block(0, k, k, 1) = coefficients;
        r(k, k) = diagonal;
        out.kept.push_back(static_cast<int>(j));
        ++k;
    }
    out.q.conservativeResize(n, k);
    out.r = r.topLeftCorner(k, k);
    return out;
}

} // namespace fsi::acceleration
