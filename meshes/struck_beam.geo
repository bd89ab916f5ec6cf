// struck_beam.geo — straight beam (0,0,0) → (L,0,0) in n segments of one 2-node element each, every
// node a named physical point, so that a scene can put a force element between any two adjacent
// nodes (issue 17's damped struck beams once had a rotational dashpot per element; they now use the
// beams' own material damping, inputs/beam_impulse_damped.yaml).
// Units: m.
// Physical groups: line "beam"; points "p0" (origin) … "pn" (x = L).
// Parameters (ONELAB, set from a scene's mesh.parameters or `gmsh -setnumber NAME VALUE`):
//   L  beam length (m), default 10
//   n  number of elements, default 10
DefineConstant[
  L = {10, Name "L"},
  n = {10, Name "n"}
];
If (!(L > 0 && L < 1e12))
  Error("parameter L = %g: expected a length > 0 (m)", L);
  Abort;
EndIf
If (!(n >= 1 && n <= 1000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements from 1 to 1000", n);
  Abort;
EndIf

For i In {0 : n}
  Point(i + 1) = {i * L / n, 0, 0};
  Physical Point(Sprintf("p%g", i)) = {i + 1};
EndFor
For i In {1 : n}
  Line(i) = {i, i + 1};
  Transfinite Curve{i} = 2;
EndFor
Physical Curve("beam") = {1 : n};
