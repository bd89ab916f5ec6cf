// cantilever.geo — straight beam from (0, 0, 0) to (L, 0, 0), meshed with n equal 2-node elements.
// Units: m.
// Physical groups: line "beam" (the whole beam); points "root" (origin), "tip" (x = L).
// Parameters (ONELAB, set from a scene's mesh.parameters or `gmsh -setnumber NAME VALUE`):
//   L  beam length (m), default 1
//   n  number of elements, default 16
// mesh.elements_per_curve overrides n; mesh.element_size does not apply (n fixes the count).
DefineConstant[
  L = {1, Name "L"},
  n = {16, Name "n"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(L > 0 && L < 1e12))
  Error("parameter L = %g: expected a length > 0 (m)", L);
  Abort;
EndIf
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements from 1 to 100000", n);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Line(1) = {1, 2};
Transfinite Curve{1} = n + 1;

Physical Curve("beam") = {1};
Physical Point("root") = {1};
Physical Point("tip") = {2};
