// SPDX-License-Identifier: GPL-3.0-or-later
// Turek-Hron CSM1 beam as a one-cell-thick 3-D slab (plane strain: u_z = 0 on both faces).
// Beam 0.35 x 0.02 m behind the cylinder r = 0.05 at (0.2, 0.2); A = (0.6, 0.2).
//   arc = 1 (default): the left end is the cylinder arc (x from 0.24899 to 0.25), clamped,
//                      as in the benchmark;
//   arc = 0: the usual simplification, a straight clamped edge at x = 0.6 - 0.35 = 0.25.
// gmsh -3 -order 2 -setnumber n 2 csm1.geo -o csm1.msh   (n Hex20 cells through the depth)
SetFactory("OpenCASCADE");
If (!Exists(n)) n = 2; EndIf
If (!Exists(arc)) arc = 1; EndIf
L = 0.35; h = 0.02; t = 0.01;
If (arc)
  Box(1) = {0.2, 0.19, 0, 0.4, h, t};
  Cylinder(2) = {0.2, 0.2, -0.01, 0, 0, t + 0.02, 0.05};
  Rotate {{0, 0, 1}, {0.2, 0.2, 0}, Pi} { Volume{2}; }   // keep the cylinder's seam off the beam
  BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Else
  Box(3) = {0.25, 0.19, 0, L, h, t};
EndIf
e = 1e-4;   // OpenCASCADE bounding boxes are slightly enlarged
all() = Curve{:};
For i In {0 : #all() - 1}
  bb() = BoundingBox Curve{all(i)};
  If (bb(3) - bb(0) > 0.5 * L)
    Transfinite Curve{all(i)} = Round(17.5 * n) + 1;
  ElseIf (bb(4) - bb(1) > 0.5 * h)
    Transfinite Curve{all(i)} = n + 1;
  Else
    Transfinite Curve{all(i)} = 2;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Mesh.SecondOrderIncomplete = 1;
Physical Volume("solid") = {3};
Physical Surface("clamped") = Surface In BoundingBox{0.2, 0.18, -e, 0.2501, 0.22, t + e};
Physical Surface("sides") = Surface In BoundingBox{0.2, 0.18, -e, 0.6 + e, 0.22, e};
Physical Surface("sides") += Surface In BoundingBox{0.2, 0.18, t - e, 0.6 + e, 0.22, t + e};
