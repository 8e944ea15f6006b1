// SPDX-License-Identifier: GPL-3.0-or-later
// One-column DGEMM and DTRSM calls (what MUMPS' solve phase makes with one right-hand side) are
// served by DGEMV / DTRSV (linalg/SparseDirectSolver.cpp): the same numbers as the products
// written out, for every transposition; other calls still reach the BLAS's own DGEMM.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

extern "C"
{
    void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                const double* alpha, const double* a, const int* lda, const double* b,
                const int* ldb, const double* beta, double* c, const int* ldc, std::size_t,
                std::size_t);
    void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag,
                const int* m, const int* n, const double* alpha, const double* a, const int* lda,
                double* b, const int* ldb, std::size_t, std::size_t, std::size_t, std::size_t);
}

namespace
{
// Column-major entry (i, j) of a matrix with leading dimension ld.
double at(const std::vector<double>& a, int ld, int i, int j)
{
    return a[static_cast<std::size_t>(j) * ld + i];
}
std::vector<double> filled(std::size_t size, double seed)
{
    std::vector<double> v(size);
    for (std::size_t i = 0; i < size; ++i)
        v[i] = std::sin(seed + 0.7 * static_cast<double>(i));
    return v;
}
} // namespace

TEST(BlasOneColumn, GemmWithOneColumnEqualsTheProduct)
{
    const int m = 7, k = 5, lda = 9, ldb = 6, ldc = 8;
    const double alpha = 1.5, beta = -0.5;
    for (const char* ta : {"N", "T"})
        for (const char* tb : {"N", "T"})
        {
            const bool transA = *ta == 'T', transB = *tb == 'T';
            const std::vector<double> a = filled(static_cast<std::size_t>(lda) * 9, 0.1);
            const std::vector<double> b = filled(static_cast<std::size_t>(ldb) * 6, 0.2);
            std::vector<double> c = filled(ldc, 0.3);
            std::vector<double> expected = c;
            for (int i = 0; i < m; ++i)
            {
                double s = 0.0;
                for (int l = 0; l < k; ++l)
                    s += (transA ? at(a, lda, l, i) : at(a, lda, i, l)) *
                         (transB ? at(b, ldb, 0, l) : at(b, ldb, l, 0));
                expected[i] = alpha * s + beta * c[i];
            }
            const int one = 1;
            dgemm_(ta, tb, &m, &one, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(),
                   &ldc, 1, 1);
            for (int i = 0; i < m; ++i)
                EXPECT_NEAR(c[i], expected[i], 1e-14) << ta << tb << " row " << i;
            for (int i = m; i < ldc; ++i) // beyond the column: untouched
                EXPECT_EQ(c[i], filled(ldc, 0.3)[i]);
        }
}

TEST(BlasOneColumn, GemmWithTwoColumnsStillWorks)
{
    const int m = 4, n = 2, k = 3;
    const double alpha = 1.0, beta = 0.0;
    const std::vector<double> a = filled(12, 0.4), b = filled(6, 0.5);
    std::vector<double> c(8, 0.0);
    dgemm_("N", "N", &m, &n, &k, &alpha, a.data(), &m, b.data(), &k, &beta, c.data(), &m, 1, 1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < m; ++i)
        {
            double s = 0.0;
            for (int l = 0; l < k; ++l)
                s += at(a, m, i, l) * at(b, k, l, j);
            EXPECT_NEAR(at(c, m, i, j), s, 1e-14);
        }
}

TEST(BlasOneColumn, TriangularSolveWithOneColumnSolves)
{
    const int m = 6, lda = 7, one = 1;
    const double alpha = 1.0;
    std::vector<double> a = filled(static_cast<std::size_t>(lda) * m, 0.6);
    for (int i = 0; i < m; ++i)
        a[static_cast<std::size_t>(i) * lda + i] += 4.0; // well conditioned
    for (const char* uplo : {"L", "U"})
        for (const char* trans : {"N", "T"})
            for (const char* diag : {"N", "U"})
            {
                const std::vector<double> x = filled(m, 0.9);
                // b = op(T) x, T the uplo triangle of a (unit diagonal for "U")
                std::vector<double> b(m, 0.0);
                for (int i = 0; i < m; ++i)
                    for (int j = 0; j < m; ++j)
                    {
                        const int r = *trans == 'T' ? j : i, c = *trans == 'T' ? i : j;
                        const bool inTriangle = *uplo == 'L' ? r >= c : r <= c;
                        if (!inTriangle)
                            continue;
                        const double t = r == c && *diag == 'U' ? 1.0 : at(a, lda, r, c);
                        b[i] += t * x[j];
                    }
                dtrsm_("L", uplo, trans, diag, &m, &one, &alpha, a.data(), &lda, b.data(), &m, 1, 1,
                       1, 1);
                for (int i = 0; i < m; ++i)
                    EXPECT_NEAR(b[i], x[i], 1e-13) << uplo << trans << diag << " row " << i;
            }
}
