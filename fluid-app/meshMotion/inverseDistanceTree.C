// SPDX-License-Identifier: GPL-3.0-or-later
// inverseDistanceTree (see inverseDistanceTree.H).
#include "inverseDistanceTree.H"

#include <algorithm>

namespace
{
constexpr Foam::label leafSize = 16; // sources per leaf at most (8 and 32 measured: no better)

Foam::scalar boxDistanceSqr(const Foam::point& x, const Foam::boundBox& bb)
{
    Foam::scalar d2 = 0;
    for (Foam::direction c = 0; c < 3; ++c)
    {
        const Foam::scalar out =
            Foam::max(Foam::max(bb.min()[c] - x[c], x[c] - bb.max()[c]), Foam::scalar(0));
        d2 += out*out;
    }
    return d2;
}
} // End anonymous namespace


Foam::inverseDistanceTree::inverseDistanceTree
(
    const pointField& sources,
    const scalarField& areas,
    const label exponent,
    const scalar openingAngle
)
:
    points_(sources),
    areas_(areas),
    exponent_(exponent),
    openingAngle_(openingAngle),
    translations_(sources.size(), Zero),
    order_(identity(sources.size()))
{
    nodes_.reserve(4*sources.size()/leafSize + 1);
    if (sources.size())
    {
        build(0, sources.size());
    }
}


Foam::label Foam::inverseDistanceTree::build(const label begin, const label end)
{
    const label index = label(nodes_.size());
    nodes_.emplace_back();
    node n;
    n.begin = begin;
    n.end = end;
    n.bb = boundBox(pointField(points_, SubList<label>(order_, end - begin, begin)), false);
    vector weighted(Zero);
    for (label k = begin; k < end; ++k)
    {
        const label i = order_[k];
        n.area += areas_[i];
        weighted += areas_[i]*points_[i];
    }
    n.centroid = n.area > 0 ? point(weighted/n.area) : n.bb.centre();
    for (label k = begin; k < end; ++k)
    {
        const label i = order_[k];
        const vector d(points_[i] - n.centroid);
        n.radius = max(n.radius, mag(d));
        n.second += areas_[i]*sqr(d);
    }
    for (direction j = 0; j < 3; ++j)
    {
        n.t2[j] = Zero;
    }
    if (end - begin > leafSize)
    {
        // median split along the box's longest side
        const vector span(n.bb.span());
        const direction axis =
            span.x() >= span.y() && span.x() >= span.z() ? 0 : (span.y() >= span.z() ? 1 : 2);
        const label mid = (begin + end)/2;
        std::nth_element
        (
            order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
            [this, axis](const label a, const label b)
            {
                return points_[a][axis] < points_[b][axis];
            }
        );
        n.left = build(begin, mid);
        n.right = build(mid, end);
    }
    nodes_[index] = n;
    return index;
}


void Foam::inverseDistanceTree::setTranslations(const vectorField& translations)
{
    translations_ = translations;
    if (openingAngle_ <= 0)
    {
        return;   // the direct sum uses no cluster moments
    }
    for (node& n : nodes_)
    {
        n.t0 = Zero;
        n.t1 = Zero;
        for (direction j = 0; j < 3; ++j)
        {
            n.t2[j] = Zero;
        }
        for (label k = n.begin; k < n.end; ++k)
        {
            const label i = order_[k];
            const vector d(points_[i] - n.centroid);
            const vector at(areas_[i]*translations[i]);
            n.t0 += at;
            n.t1 += d*at;
            const symmTensor dd(sqr(d));
            for (direction j = 0; j < 3; ++j)
            {
                n.t2[j] += at[j]*dd;
            }
        }
    }
}


Foam::label Foam::inverseDistanceTree::nearest(const point& x, scalar& r2) const
{
    r2 = GREAT;
    label best = -1;
    if (nodes_.empty())
    {
        return best;
    }
    label stack[128];
    label top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
        const node& n = nodes_[stack[--top]];
        if (boxDistanceSqr(x, n.bb) >= r2)
        {
            continue;
        }
        if (n.left < 0)
        {
            for (label k = n.begin; k < n.end; ++k)
            {
                const scalar d2 = magSqr(x - points_[order_[k]]);
                if (d2 < r2)
                {
                    r2 = d2;
                    best = order_[k];
                }
            }
            continue;
        }
        // the nearer child on top
        const bool leftFirst =
            boxDistanceSqr(x, nodes_[n.left].bb) <= boxDistanceSqr(x, nodes_[n.right].bb);
        stack[top++] = leftFirst ? n.right : n.left;
        stack[top++] = leftFirst ? n.left : n.right;
    }
    return best;
}

// ************************************************************************* //
