// SPDX-License-Identifier: GPL-3.0-or-later
// Turek-Hron FSI1 beam: a 3-D slab ONE element thick in z (plane strain is imposed by the
// config: u_z = 0 on both z faces). The beam runs from its attachment on the cylinder
// (x = 0.2 + sqrt(0.05^2 - 0.01^2) = 0.248990 m, where the beam's top and bottom faces meet
// the cylinder; the clamp is the straight end there) to the tip x = 0.6 m; y 0.19 .. 0.21 m;
// z 0 .. depth, depth = the fluid mesh's depth (cases/turek-hron-cfd1/blockMesh.py DEPTH = 0.01 m) so that the
// two interfaces coincide.
//   gmsh -3 -order 2 -setnumber nx 35 -setnumber ny 2 beam.geo -o beam.msh
// nx cells along the beam, ny (even: a node row on y = 0.2, through point A) across it;
// -order 2 with Mesh.SecondOrderIncomplete = 1 gives Hex20 (set it to 0 for Hex27).
// Physical groups: volume "solid"; surfaces "clamped" (x = x0), "wetted" (top, bottom, tip:
// the faces touching the fluid), "front" (z = 0) and "back" (z = depth).
If (!Exists(nx)) nx = 35; EndIf
If (!Exists(ny)) ny = 2; EndIf
If (!Exists(depth)) depth = 0.01; EndIf
If (!Exists(incomplete)) incomplete = 1; EndIf
x0 = 0.2 + Sqrt(0.05^2 - 0.01^2);
x1 = 0.6;
y0 = 0.19;
y1 = 0.21;

Point(1) = {x0, y0, 0};
Point(2) = {x1, y0, 0};
Point(3) = {x1, y1, 0};
Point(4) = {x0, y1, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // tip
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // clamped end
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

// ext[0] = back face (z = depth), ext[1] = volume, ext[2..5] = sides from lines 1..4
ext[] = Extrude {0, 0, depth} { Surface{1}; Layers{1}; Recombine; };

Mesh.SecondOrderIncomplete = incomplete;
Physical Volume("solid") = {ext[1]};
Physical Surface("clamped") = {ext[5]};
Physical Surface("wetted") = {ext[2], ext[3], ext[4]};
Physical Surface("front") = {1};
Physical Surface("back") = {ext[0]};
