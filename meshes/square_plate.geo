// square_plate.geo — the square [0, a]² in the x-y plane as four transfinite quarters around its
// centre, 2n × 2n quadrilaterals (triangles with quads = 0). Units: m.
// Physical groups: surface "plate"; curve "edges" (the whole boundary); points "centre" (a/2, a/2),
// "corner" (0, 0) and "far_corner" (a, a).
// Parameters: a (1 m), n (8: elements per quarter side), quads (1 or 0).
DefineConstant[
  a = {1, Name "a"},
  n = {8, Name "n"},
  quads = {1, Name "quads"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(a > 0 && a < 1e12))
  Error("parameter a = %g: expected a side > 0 (m)", a);
  Abort;
EndIf
If (!(n >= 1 && n <= 10000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per side from 1 to 10000", n);
  Abort;
EndIf
If (!(quads == 0 || quads == 1))
  Error("parameter quads = %g: expected 0 or 1", quads);
  Abort;
EndIf

Point(1) = {0, 0, 0};     Point(2) = {a / 2, 0, 0};     Point(3) = {a, 0, 0};
Point(4) = {0, a / 2, 0}; Point(5) = {a / 2, a / 2, 0}; Point(6) = {a, a / 2, 0};
Point(7) = {0, a, 0};     Point(8) = {a / 2, a, 0};     Point(9) = {a, a, 0};
Line(1) = {1, 2}; Line(2) = {2, 3};             // bottom
Line(3) = {4, 5}; Line(4) = {5, 6};             // middle (horizontal)
Line(5) = {7, 8}; Line(6) = {8, 9};             // top
Line(7) = {1, 4}; Line(8) = {4, 7};             // left
Line(9) = {2, 5}; Line(10) = {5, 8};            // middle (vertical)
Line(11) = {3, 6}; Line(12) = {6, 9};           // right
Curve Loop(1) = {1, 9, -3, -7};  Plane Surface(1) = {1};
Curve Loop(2) = {2, 11, -4, -9}; Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -8}; Plane Surface(3) = {3};
Curve Loop(4) = {4, 12, -6, -10}; Plane Surface(4) = {4};
Transfinite Curve{1:12} = n + 1;
Transfinite Surface{1:4};
If (quads)
  Recombine Surface{1:4};
EndIf

Physical Surface("plate") = {1, 2, 3, 4};
Physical Curve("edges") = {1, 2, 5, 6, 7, 8, 11, 12};
Physical Point("centre") = {5};
Physical Point("corner") = {1};
Physical Point("far_corner") = {9};
