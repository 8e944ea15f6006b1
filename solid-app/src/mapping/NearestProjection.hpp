// SPDX-License-Identifier: GPL-3.0-or-later
//
// nearest-projection: each target point takes the value that the source surface's own shape
// functions give at the point's closest point on that surface. The source surface is the solid's
// wetted faces (Tri3/Tri6/Quad4/Quad8/Quad9, node indices into the source cloud), given with
// setSourceSurface() before compute(). Row t of H holds N_a(xi_t) for the nodes a of the face
// closest to target point t, xi_t its local coordinates there (Gauss-Newton on |X(xi) - x_t|^2,
// kept inside the face). So:
//   - consistent: the displaced fluid surface follows the solid's finite-element surface; every
//     field of the faces' interpolation space (constants, linear fields, on straight-sided
//     quadratic faces quadratic ones) is reproduced exactly at points on the surface; a point at
//     distance d off it takes the value at its projection;
//   - conservative (H^T): each face force goes to the nodes of its face with the shape-function
//     weights of its projection (the consistent nodal load); total force exactly; total moment
//     up to sum (x_t - X(xi_t)) x f_t, i.e. exactly for forces along the surface normal.
// No radius and no linear solve: set-up is a search per target point, an apply a sparse product.
//
// blend > 0 makes the map continuous off the surface as well. Inside a convex edge of the source
// (a fluid surface that cuts the solid's sharp corner) the closest face switches where two faces
// are equally far, and the value jumps by about |grad u| times the distance between the two
// projections. With blend b, every candidate face f whose distance d_f is within (1 + b) d_min of
// the closest one's contributes with weight (1 - s)^2, s = (d_f - d_min) / (b d_min), the weights
// normalised to one: the jump is spread over a band of width ~b d_min, and the mapped value's slope
// stays a few |grad u| (on a 90 deg edge 2-6 mm inside: 2.6 |grad u| with b = 1, 3.8 with 0.5,
// 491 with the closest face alone; test_nearest_projection bounds them by 3, 4.5 and 50). Points on
// the surface (d_min = 0) keep exactly the closest face's value, so the reproduction and
// conservation properties above are unchanged; a point at distance d off the surface takes a
// weighted mean of values within ~(2b + b^2)^(1/2) d of its projection instead of the value at the
// projection.
#pragma once

#include "mapping/SparseMapping.hpp"

#include <vector>

namespace fsi::mapping
{

class NearestProjection;

struct NearestProjectionParameters
{
    static constexpr const char* keyword = "nearest-projection";
    using Strategy = NearestProjection;
    // Faces examined per target point: those whose centroids are the nearest this many; the
    // closest point is searched on each. In [1, 200].
    int candidateFaces = 24;
    // Relative width of the band in which equally close faces are blended (see above). 0 = the
    // closest face only. In [0, 10].
    double blend = 0.0;

    static const std::vector<std::string>& keys();
    static NearestProjectionParameters parse(const config::Block& layer);
    // Throws std::runtime_error naming mapping.nearest-projection.<key> and the fix.
    void validate() const;
    std::string echo() const;
};

class NearestProjection final : public SparseMapping
{
public:
    explicit NearestProjection(const NearestProjectionParameters& params = {});
    std::string name() const override { return "nearest-projection"; }
    void setSourceSurface(const SourceSurface& surface) override;
    // Pre: setSourceSurface() done with faces whose node indices are < source.rows(). Throws
    // std::runtime_error (one line) for no faces, a stray index or a non-surface face type.
    void compute(const PointCloud& source, const PointCloud& target) override;

    // Largest and root-mean-square distance [m] from a target point to its projection (how far
    // the two discretised surfaces lie apart).
    double maxDistance() const { return maxDistance_; }
    double rmsDistance() const { return rmsDistance_; }

private:
    NearestProjectionParameters params_;
    SourceSurface surface_; // empty until setSourceSurface()
    double maxDistance_ = 0.0;
    double rmsDistance_ = 0.0;
};

} // namespace fsi::mapping
