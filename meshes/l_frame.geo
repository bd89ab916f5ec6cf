// l_frame.geo — an L-shaped frame of two straight members in the x-y plane: the arm from the root
// (0, 0, 0) to the corner (a, 0, 0), the leg from the corner to the tip (a, b, 0). Units: m.
// Physical groups: lines "arm", "leg" (one member each) and "frame" (both: the same curves, for a
// scene that gives the two members one section); points "root", "corner", "tip".
// Parameters (ONELAB, set from a scene's mesh.parameters or `gmsh -setnumber NAME VALUE`):
//   a  arm length (m), default 0.4
//   b  leg length (m), default 0.25
//   n  elements per member, default 8
DefineConstant[
  a = {0.4, Name "a"},
  b = {0.25, Name "b"},
  n = {8, Name "n"}
];
If (!(a > 0 && a < 1e12 && b > 0 && b < 1e12))
  Error("parameters a = %g, b = %g: expected lengths > 0 (m)", a, b);
  Abort;
EndIf
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements from 1 to 100000", n);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {a, b, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Transfinite Curve{1, 2} = n + 1;

Physical Curve("arm") = {1};
Physical Curve("leg") = {2};
Physical Curve("frame") = {1, 2};
Physical Point("root") = {1};
Physical Point("corner") = {2};
Physical Point("tip") = {3};
