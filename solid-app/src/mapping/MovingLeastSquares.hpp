// SPDX-License-Identifier: GPL-3.0-or-later
//
// moving-least-squares: each target point takes the value, at its own position, of the linear
// field a + B (x - c) fitted by weighted least squares to the source nodes around it. The stencil
// is the source nodes within R of the target, R = radius_factor times the distance to its
// `neighbours`-th nearest source node; weights (1 - (r/R)^2)^2, coordinates about the stencil's
// weighted centre c and scaled by R. Directions the stencil hardly spans (singular values below
// `cutoff` times the largest: across a gently curved surface patch) are left out of the fit, so a
// target off the source surface takes the surface's value carried along the normal, not a
// gradient the nodes do not determine. So:
//   - H depends only on the source nodes and the target's position, not on the other targets: a
//     finer fluid mesh samples the same field (unlike target-side smoothing, TargetSmoothing.hpp);
//   - H reproduces constants and every linear field the stencil spans exactly (all three
//     directions in the solid's thin trailing edge, whose two sides are both in the stencil);
//   - R and the weights vary continuously with the target's position: no jumps between
//     neighbouring targets;
//   - conservative (H^T): total force exactly, total moment too where H reproduces linear fields.
// Where the fluid surface lies inside the solid's (the hydrofoil's sharp fluid trailing edge in
// the solid's 0.4 mm blunt one), a point takes the linear field through the section, i.e. the
// material's bending and twist there; the closest point of the solid surface (nearest-projection)
// gives it the surface value 0.2 mm away instead (cases/hydrofoil/README.md, "The trailing edge's
// share").
// Set-up: one k-nearest search and one (<= 4k) x 4 singular value decomposition per target; an
// apply is one sparse product.
#pragma once

#include "mapping/SparseMapping.hpp"

#include <string>
#include <vector>

namespace fsi::mapping
{

class MovingLeastSquares;

struct MovingLeastSquaresParameters
{
    static constexpr const char* keyword = "moving-least-squares";
    using Strategy = MovingLeastSquares;
    // The stencil's size: R = radiusFactor times the distance to the neighbours-th nearest source
    // node (and at most the distance to the 4 neighbours-th). In [4, 100].
    int neighbours = 12;
    // In [1.05, 5]: > 1 so that the neighbours-th node still has weight.
    double radiusFactor = 1.5;
    // Relative singular-value cutoff of the fit, in (0, 0.5]; 1e-2 leaves the normal of a surface
    // patch curved by less than about a hundredth of R out.
    double cutoff = 1e-2;

    static const std::vector<std::string>& keys();
    static MovingLeastSquaresParameters parse(const config::Block& layer);
    // Throws std::runtime_error naming mapping.moving-least-squares.<key> and the fix.
    void validate() const;
    std::string echo() const;
};

class MovingLeastSquares final : public SparseMapping
{
public:
    explicit MovingLeastSquares(const MovingLeastSquaresParameters& params = {});
    std::string name() const override { return "moving-least-squares"; }
    // Throws std::runtime_error (one line) for fewer than 4 source points.
    void compute(const PointCloud& source, const PointCloud& target) override;

    // Largest distance [m] from a target point to its nearest source node.
    double maxGap() const { return maxGap_; }

private:
    MovingLeastSquaresParameters params_;
    double maxGap_ = 0.0;
};

} // namespace fsi::mapping
