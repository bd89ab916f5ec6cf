// sze_strip.geo — flat strip [0, L] × [0, b] in the x-y plane, nx × ny quadrilaterals: the
// cantilever strips of Sze, Liu & Lo (2004), Sec. 3.1 (end shear, L = 10) and 3.2 (end moment,
// roll-up, L = 12), both b = 1 and meshed 16 × 1 in the paper. Units: m.
// Physical groups: surface "strip"; curves "root" (x = 0), "tip" (x = L), "side_a" (y = 0) and
// "side_b" (y = b); points "root_a" (0, 0), "tip_a" (L, 0) and "tip_b" (L, b).
// Parameters: L (10 m), b (1 m), nx (16), ny (1), quads (1: quadrilaterals, 0: triangles).
DefineConstant[
  L = {10, Name "L"},
  b = {1, Name "b"},
  nx = {16, Name "nx"},
  ny = {1, Name "ny"},
  quads = {1, Name "quads"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(L > 0 && L < 1e12))
  Error("parameter L = %g: expected a length > 0 (m)", L);
  Abort;
EndIf
If (!(b > 0 && b < 1e12))
  Error("parameter b = %g: expected a width > 0 (m)", b);
  Abort;
EndIf
If (!(nx >= 1 && nx <= 10000 && nx == Round(nx)))
  Error("parameter nx = %g: expected a whole number of elements along the strip from 1 to 10000", nx);
  Abort;
EndIf
If (!(ny >= 1 && ny <= 10000 && ny == Round(ny)))
  Error("parameter ny = %g: expected a whole number of elements across from 1 to 10000", ny);
  Abort;
EndIf
If (!(quads == 0 || quads == 1))
  Error("parameter quads = %g: expected 0 or 1", quads);
  Abort;
EndIf
If (!(nx * ny <= 10000000))
  Error("parameters give %g elements: expected at most 1e+07", nx * ny);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, b, 0};
Point(4) = {0, b, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
If (quads)
  Recombine Surface{1};
EndIf

Physical Surface("strip") = {1};
Physical Curve("root") = {4};
Physical Curve("tip") = {2};
Physical Curve("side_a") = {1};
Physical Curve("side_b") = {3};
Physical Point("root_a") = {1};
Physical Point("tip_a") = {2};
Physical Point("tip_b") = {3};
