// bend45.geo — 45° circular bend of Bathe & Bolourchi (1979): an arc of radius R in the x-y plane,
// centre (0, R, 0), from (0, 0, 0) (tangent +x) to (R sin45°, R (1 - cos45°), 0), meshed with n
// 2-node elements equal in arc length (their nodes lie on the arc, the segments are chords).
// Units: m, like every mesh here; the benchmark's data (R = 100 in, E = 1e7 psi) are in inches
// and pounds: a scene that keeps them must use them consistently.
// Physical groups: line "bend"; points "root" (origin, clamped in the benchmark), "tip" (free end).
// Parameters (ONELAB, set from a scene's mesh.parameters or `gmsh -setnumber NAME VALUE`):
//   R  radius (m), default 100
//   n  number of elements, default 8
// mesh.elements_per_curve overrides n; mesh.element_size does not apply (n fixes the count).
DefineConstant[
  R = {100, Name "R"},
  n = {8, Name "n"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(R > 0 && R < 1e12))
  Error("parameter R = %g: expected a radius > 0 (m)", R);
  Abort;
EndIf
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements from 1 to 100000", n);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {0, R, 0};                                // centre
Point(3) = {R * Sin(Pi / 4), R * (1 - Cos(Pi / 4)), 0};
Circle(1) = {1, 2, 3};
Transfinite Curve{1} = n + 1;

Physical Curve("bend") = {1};
Physical Point("root") = {1};
Physical Point("tip") = {3};
