// SPDX-License-Identifier: GPL-3.0-or-later
// Point clouds for the mapping tests: the same surfaces sampled differently on the two sides;
// and the fields and measures the tests map and compare.
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace fsi::mapping::test
{

// Cylinder of radius 0.5 m and length 1 m, axis along z through (1, -2, 0.5) m (off the origin
// on purpose). nTheta x nZ points; theta shifted by thetaShift of a step, z from zLo to zHi.
inline PointCloud cylinder(int nTheta, int nZ, double thetaShift, double zLo, double zHi)
{
    const double pi = std::acos(-1.0);
    PointCloud p(nTheta * nZ, 3);
    for (int j = 0; j < nZ; ++j)
        for (int i = 0; i < nTheta; ++i)
        {
            const double theta = 2.0 * pi * (i + thetaShift) / nTheta;
            const double z = nZ == 1 ? zLo : zLo + (zHi - zLo) * j / (nZ - 1);
            p.row(j * nTheta + i) << 1.0 + 0.5 * std::cos(theta), -2.0 + 0.5 * std::sin(theta), z;
        }
    return p;
}

// Solid side: nTheta x nTheta/2 nodes, ends included.
inline PointCloud solidCylinder(int nTheta)
{
    return cylinder(nTheta, nTheta / 2 + 1, 0.0, 0.0, 1.0);
}

// Fluid side: a different sampling, 1.5x denser, rotated by 0.37 of its step, axially at
// the centres of 3 nTheta / 4 equal cells (faces centres-like). Pre: nTheta multiple of 4.
// Self-similar under doubling of nTheta (clean convergence rates).
inline PointCloud fluidCylinder(int nTheta)
{
    const int m = 3 * nTheta / 2, mz = 3 * nTheta / 4;
    return cylinder(m, mz, 0.37, 0.5 / mz, 1.0 - 0.5 / mz);
}

// Flat plate z = 0.2 m, [0, lx] x [0, ly], nx x ny nodes shifted by (dx, dy).
inline PointCloud plate(int nx, int ny, double lx, double ly, double dx, double dy)
{
    PointCloud p(nx * ny, 3);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            p.row(j * nx + i) << dx + lx * i / (nx - 1), dy + ly * j / (ny - 1), 0.2;
    return p;
}

// L-shaped interface: floor z = offset and wall x = offset, each 1 m x 1 m with n x n points
// (spacing 1/n m, shifted by shift of a step). Patches inside the floor or the wall are
// coplanar: they resolve 3 of the 4 linear functions of the whole interface.
inline PointCloud corner(int n, double shift, double offset)
{
    PointCloud p(2 * n * n, 3);
    Eigen::Index row = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const double u = (i + shift + 0.5) / n, v = (j + shift) / n;
            p.row(row++) << u, v, offset; // floor
            p.row(row++) << offset, v, u; // wall
        }
    return p;
}

// f(x) = a + B x, three components (every mapping that reproduces linear fields maps it exactly).
inline Values linearField(const PointCloud& x)
{
    Eigen::Matrix3d b;
    b << 1.5, -2.0, 0.25, 0.5, 3.0, -1.0, -0.75, 0.1, 2.0;
    const Eigen::RowVector3d a(0.3, -1.2, 4.0);
    return (x * b.transpose()).rowwise() + a;
}

// max |got - want| / max |want| over all entries.
inline double relativeMaxError(const Values& got, const Values& want)
{
    return (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
}

// Sum of x_i x f_i about the origin.
inline Eigen::Vector3d totalMoment(const PointCloud& x, const Values& f)
{
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        m += Eigen::Vector3d(x.row(i)).cross(Eigen::Vector3d(f.row(i)));
    return m;
}

// Forces on n fluid faces: deterministic, mixed signs, not smooth.
inline Values faceForces(Eigen::Index n)
{
    Values g(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        g.row(i) << std::sin(1.7 * i), std::cos(0.3 * i) + 0.2, 0.5 - std::sin(2.9 * i + 1.0);
    return g;
}

} // namespace fsi::mapping::test
