// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app's prescribed interface motions (fluid-app/coupling/prescribedTransport.C), without
// OpenFOAM: the closed-form displacement of single points, and the exact property of a twist
// (each section normal to the beam axis moves rigidly).
#include "couplingTransport.H"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using fsi::fluid::prescribedDisplacement;
using fsi::fluid::PrescribedMotion;

namespace
{
const double kPi = std::acos(-1.0);

PrescribedMotion twistAboutZ(double angleDeg, double amplitude)
{
    PrescribedMotion m;
    m.type = "twist";
    m.origin[0] = 1.0; // the twist axis: the line x = 1, y = 0 along z
    m.beamAxis[0] = 0;
    m.beamAxis[2] = 1;
    m.direction[0] = 0;
    m.direction[1] = -1;
    m.start = 0;
    m.length = 2.0;
    m.angleDeg = angleDeg;
    m.amplitude = amplitude;
    return m;
}

double distance(const std::vector<double>& p, const std::vector<double>& d, int a, int b)
{
    double s = 0;
    for (int j = 0; j < 3; ++j)
    {
        const double e = (p[3 * a + j] + d[3 * a + j]) - (p[3 * b + j] + d[3 * b + j]);
        s += e * e;
    }
    return std::sqrt(s);
}
} // namespace

TEST(PrescribedMotion, TwistTurnsEachSectionByItsLinearAngle)
{
    // a point 0.5 m ahead of the axis at z = 1 (xi = 0.5): turned by half of 10 deg
    const std::vector<double> p = {0.5, 0.0, 1.0};
    const auto d = prescribedDisplacement(twistAboutZ(10.0, 0.0), p, 1.0);
    const double theta = 5.0 * kPi / 180.0;
    EXPECT_NEAR(d[0], -0.5 * std::cos(theta) + 0.5, 1e-15);
    EXPECT_NEAR(d[1], -0.5 * std::sin(theta), 1e-15);
    EXPECT_NEAR(d[2], 0.0, 1e-15);
    // half the fraction: half the angle
    const auto h = prescribedDisplacement(twistAboutZ(10.0, 0.0), p, 0.5);
    EXPECT_NEAR(h[1], -0.5 * std::sin(theta / 2), 1e-15);
}

TEST(PrescribedMotion, TwistLeavesTheClampAndMovesSectionsRigidly)
{
    // four points of one section (z = 1.5) and one on the clamp plane (z = 0)
    const std::vector<double> p = {0.9, 0.02, 1.5, 1.04, -0.01, 1.5,  0.96, 0.03,
                                   1.5, 1.01, 0.0, 1.5,  0.7,   0.05, 0.0};
    const auto m = twistAboutZ(-12.0, 0.03);
    const auto d = prescribedDisplacement(m, p, 1.0);
    for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
        {
            std::vector<double> zero(p.size(), 0.0);
            EXPECT_NEAR(distance(p, d, a, b), distance(p, zero, a, b), 1e-15);
        }
    for (int j = 0; j < 3; ++j)
        EXPECT_EQ(d[12 + j], 0.0); // at the clamp nothing moves
    // the bending term: a point on the axis moves by amplitude xi^2 along direction only
    const std::vector<double> axis = {1.0, 0.0, 2.0};
    const auto e = prescribedDisplacement(m, axis, 1.0);
    EXPECT_NEAR(e[0], 0.0, 1e-15);
    EXPECT_NEAR(e[1], -0.03, 1e-15);
    EXPECT_NEAR(e[2], 0.0, 1e-15);
}

TEST(PrescribedMotion, RotationAndBendingAsBefore)
{
    PrescribedMotion r;
    r.type = "rotation";
    r.angleDeg = 90.0; // about z through the origin: (1, 0, 0) -> (0, 1, 0)
    const auto d = prescribedDisplacement(r, {1.0, 0.0, 0.3}, 1.0);
    EXPECT_NEAR(d[0], -1.0, 1e-15);
    EXPECT_NEAR(d[1], 1.0, 1e-15);
    EXPECT_NEAR(d[2], 0.0, 1e-15);

    PrescribedMotion b;
    b.type = "bending"; // beam along x, deflection along y, 0.2 m at x = 1
    b.amplitude = 0.2;
    const auto e = prescribedDisplacement(b, {0.5, 0.0, 0.0, -0.5, 0.0, 0.0}, 1.0);
    EXPECT_NEAR(e[1], 0.05, 1e-15);
    EXPECT_EQ(e[4], 0.0);
    EXPECT_EQ(e[0], 0.0);
}
