// SPDX-License-Identifier: GPL-3.0-or-later
// Unit cube for the uniaxial creep check (symmetry planes x0, y0, z0; load face x1).
// gmsh -3 -order 2 cube.geo -o cube.msh   (2 x 2 x 2 Hex20)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Mesh.SecondOrderIncomplete = 1;
e = 1e-4;
Physical Volume("solid") = {1};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("x1") = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, 1 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 1 + e};
Physical Surface("z0") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
