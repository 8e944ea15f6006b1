// SPDX-License-Identifier: GPL-3.0-or-later
#include "andersonMixer.H"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace fsi
{
namespace fluid
{

namespace
{

// Solves the small symmetric system A gamma = b (m <= depth) by Gaussian elimination with
// partial pivoting; a vanishing pivot leaves its coefficient 0.
std::vector<double> solveSmall(std::vector<double> a, std::vector<double> b)
{
    const std::size_t m = b.size();
    auto at = [&](std::size_t r, std::size_t c) -> double& { return a[r*m + c]; };
    for (std::size_t c = 0; c < m; ++c)
    {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < m; ++r)
        {
            if (std::abs(at(r, c)) > std::abs(at(pivot, c)))
            {
                pivot = r;
            }
        }
        if (pivot != c)
        {
            for (std::size_t j = 0; j < m; ++j)
            {
                std::swap(at(c, j), at(pivot, j));
            }
            std::swap(b[c], b[pivot]);
        }
        if (at(c, c) == 0.0)
        {
            continue;
        }
        for (std::size_t r = c + 1; r < m; ++r)
        {
            const double l = at(r, c)/at(c, c);
            for (std::size_t j = c; j < m; ++j)
            {
                at(r, j) -= l*at(c, j);
            }
            b[r] -= l*b[c];
        }
    }
    std::vector<double> x(m, 0.0);
    for (std::size_t k = m; k-- > 0;)
    {
        double s = b[k];
        for (std::size_t j = k + 1; j < m; ++j)
        {
            s -= at(k, j)*x[j];
        }
        x[k] = at(k, k) == 0.0 ? 0.0 : s/at(k, k);
    }
    return x;
}

std::vector<double> difference(const std::vector<double>& a, const std::vector<double>& b)
{
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        d[i] = a[i] - b[i];
    }
    return d;
}

} // namespace

AndersonMixer::AndersonMixer(int depth, double maxCoefficientSum)
:
    depth_(depth), maxCoefficientSum_(maxCoefficientSum)
{
    if (depth < 1 || !(maxCoefficientSum > 0))
    {
        throw std::invalid_argument("AndersonMixer: depth must be >= 1 and maxCoefficientSum > 0");
    }
}

void AndersonMixer::reset()
{
    dG_.clear();
    dF_.clear();
    havePrevious_ = false;
}

AndersonMixer::Step AndersonMixer::mix
(
    std::vector<double>& g,
    const std::vector<double>& f,
    const SumAcrossRanks& sum
)
{
    Step step;
    if (havePrevious_)
    {
        if (g.size() != gPrevious_.size() || f.size() != fPrevious_.size())
        {
            throw std::invalid_argument("AndersonMixer: the state's size changed without reset()");
        }
        dG_.push_back(difference(g, gPrevious_));
        dF_.push_back(difference(f, fPrevious_));
        if (static_cast<int>(dG_.size()) > depth_)
        {
            dG_.pop_front();
            dF_.pop_front();
        }
    }
    gPrevious_ = g;
    fPrevious_ = f;
    havePrevious_ = true;
    const std::size_t m = dF_.size();
    if (m == 0)
    {
        return step;
    }
    // normal equations: Gram matrix of the residual differences and their products with f,
    // one reduction for all of them
    std::vector<double> sums(m*(m + 1)/2 + m, 0.0);
    std::size_t k = 0;
    for (std::size_t i = 0; i < m; ++i)
    {
        for (std::size_t j = 0; j <= i; ++j, ++k)
        {
            double s = 0.0;
            for (std::size_t n = 0; n < f.size(); ++n)
            {
                s += dF_[i][n]*dF_[j][n];
            }
            sums[k] = s;
        }
    }
    for (std::size_t i = 0; i < m; ++i, ++k)
    {
        double s = 0.0;
        for (std::size_t n = 0; n < f.size(); ++n)
        {
            s += dF_[i][n]*f[n];
        }
        sums[k] = s;
    }
    sum(sums);
    std::vector<double> gram(m*m), rhs(m);
    double trace = 0.0;
    k = 0;
    for (std::size_t i = 0; i < m; ++i)
    {
        for (std::size_t j = 0; j <= i; ++j, ++k)
        {
            gram[i*m + j] = gram[j*m + i] = sums[k];
        }
        trace += gram[i*m + i];
    }
    for (std::size_t i = 0; i < m; ++i, ++k)
    {
        rhs[i] = sums[k];
    }
    if (!(trace > 0.0))
    {
        return step; // no change between the last sweeps' residuals: nothing to fit
    }
    for (std::size_t i = 0; i < m; ++i)
    {
        gram[i*m + i] += 1e-12*trace; // differences that are (nearly) parallel stay solvable
    }
    const std::vector<double> gamma = solveSmall(gram, rhs);
    double size = 0.0;
    for (double c : gamma)
    {
        size += std::abs(c);
    }
    step.coefficientSum = size;
    if (!std::isfinite(size) || size > maxCoefficientSum_)
    {
        step.restarted = true;
        dG_.clear();
        dF_.clear();
        return step;
    }
    for (std::size_t i = 0; i < m; ++i)
    {
        for (std::size_t n = 0; n < g.size(); ++n)
        {
            g[n] -= gamma[i]*dG_[i][n];
        }
    }
    step.columns = static_cast<int>(m);
    return step;
}

} // namespace fluid
} // namespace fsi
