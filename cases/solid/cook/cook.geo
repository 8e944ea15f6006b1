// SPDX-License-Identifier: GPL-3.0-or-later
// Cook's membrane: tapered panel (0,0)-(48,44)-(48,60)-(0,44), one cell thick (t = 1),
// clamped at x = 0, vertical shear on x = 48; C = (48, 60) is the reported corner.
// gmsh -3 -order 2 -setnumber n 8 -setnumber hex 1 cook.geo -o cook.msh
//   n: cells per side; hex 1: hexahedra (else Tet10 from extruded triangles);
//   hex27 1: Hex27 (Gmsh's plain "-order 2"), else Hex20 (Mesh.SecondOrderIncomplete = 1).
If (!Exists(n)) n = 4; EndIf
If (!Exists(hex)) hex = 1; EndIf
If (!Exists(hex27)) hex27 = 0; EndIf
t = 1;
Point(1) = {0, 0, 0};
Point(2) = {48, 44, 0};
Point(3) = {48, 60, 0};
Point(4) = {0, 44, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
If (hex)
  Recombine Surface{1};
  out[] = Extrude {0, 0, t} { Surface{1}; Layers{1}; Recombine; };
  Mesh.SecondOrderIncomplete = !hex27;
Else
  out[] = Extrude {0, 0, t} { Surface{1}; Layers{1}; };
EndIf
// out: [0] top face, [1] volume, [2..5] sides from lines 1..4
Physical Volume("solid") = {out[1]};
Physical Surface("clamped") = {out[5]};
Physical Surface("load") = {out[3]};
Physical Surface("faces") = {1, out[0]};
