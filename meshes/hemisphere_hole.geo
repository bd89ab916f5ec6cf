// hemisphere_hole.geo — a quarter of the hemispherical shell with an 18° hole of Sze, Liu & Lo
// (2004), Sec. 3.4 (MacNeal & Harder 1985): sphere of radius R centred at the origin, from the
// equator (z = 0) up to the hole's edge at 18° from the pole (z = R cos 18°), x ≥ 0, y ≥ 0.
// n × n quadrilaterals (16 × 16 in the paper). Units: m.
// Physical groups: surface "shell"; curves "sym_y" (the meridian in the plane y = 0) and "sym_x"
// (in x = 0), "equator", "hole"; points "A" (R, 0, 0), "B" (0, R, 0), "top" (0, R sin 18°, R cos 18°).
// Parameters: R (10 m), n (16), quads (1 or 0).
DefineConstant[
  R = {10, Name "R"},
  n = {16, Name "n"},
  quads = {1, Name "quads"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(R > 0 && R < 1e12))
  Error("parameter R = %g: expected a radius > 0 (m)", R);
  Abort;
EndIf
If (!(n >= 1 && n <= 10000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per edge from 1 to 10000", n);
  Abort;
EndIf
If (!(quads == 0 || quads == 1))
  Error("parameter quads = %g: expected 0 or 1", quads);
  Abort;
EndIf
c18 = Cos(18 * Pi / 180);
s18 = Sin(18 * Pi / 180);

Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};             // A
Point(3) = {0, R, 0};             // B
Point(4) = {0, R * s18, R * c18};  // top of the meridian through B
Point(5) = {R * s18, 0, R * c18};  // top of the meridian through A
Point(6) = {0, 0, R * c18};       // centre of the hole's circle
Circle(1) = {2, 1, 3};            // equator
Circle(2) = {3, 1, 4};            // meridian in x = 0
Circle(3) = {4, 6, 5};            // hole edge
Circle(4) = {5, 1, 2};            // meridian in y = 0
Curve Loop(1) = {1, 2, 3, 4};
Surface(1) = {1} In Sphere {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
If (quads)
  Recombine Surface{1};
EndIf

Physical Surface("shell") = {1};
Physical Curve("equator") = {1};
Physical Curve("sym_x") = {2};
Physical Curve("hole") = {3};
Physical Curve("sym_y") = {4};
Physical Point("A") = {2};
Physical Point("B") = {3};
Physical Point("top") = {4};
