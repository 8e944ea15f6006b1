// SPDX-License-Identifier: GPL-3.0-or-later
// Slender cantilever 2 x 0.1 x 0.1 m along x, clamped at x = 0, shear load on x = L.
// gmsh -3 -order 2 -setnumber n 2 -setnumber hex 0 beam.geo -o beam.msh
//   n: cells through the depth (20 n along the length); hex 1: Hex20 (else Tet10).
SetFactory("OpenCASCADE");
L = 2; h = 0.1; b = 0.1;
If (!Exists(n)) n = 2; EndIf
If (!Exists(hex)) hex = 0; EndIf
Box(1) = {0, -h/2, -b/2, L, h, b};
e = 1e-6;
all() = Curve In BoundingBox{-e, -h, -b, L + e, h, b};
For i In {0 : #all() - 1}
  bb() = BoundingBox Curve{all(i)};
  If (bb(3) - bb(0) > 0.5 * L)
    Transfinite Curve{all(i)} = 20 * n + 1;
  Else
    Transfinite Curve{all(i)} = n + 1;
  EndIf
EndFor
Transfinite Surface{:};
If (hex)
  Recombine Surface{:};
  Mesh.SecondOrderIncomplete = 1;
EndIf
Transfinite Volume{1};
Physical Volume("solid") = {1};
Physical Surface("clamped") = Surface In BoundingBox{-e, -h, -b, e, h, b};
Physical Surface("tip") = Surface In BoundingBox{L - e, -h, -b, L + e, h, b};
