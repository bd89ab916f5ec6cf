// slider_crank_links.geo — the links of the slider-crank of Arnold & Brüls (2007, Sec. 5.1) as beams,
// in the initial configuration θ1 = π/2 (benchmarks.md §1): crank O (0, 0) – H (l1 cos θ1, l1 sin θ1),
// connecting rod A (= H) – mid – B (x3, 0), x3 = l1 cos θ1 + sqrt(l2² − (l1 sin θ1)²). Units: m.
// Coincident points are separate nodes (the crank tip H and the rod end A), so that the links are
// joined only by the scene's revolute joint. The rod is two curves meeting at "mid" (a node for a
// sensor): mesh.elements = N gives it 2N elements.
// Physical groups: curve "rod" (A–B), points "A", "mid", "B"; with crank = 1 also curve "crank"
// (O–H) and points "O", "H".
// Parameters (ONELAB): l1 (0.3), l2 (0.6), theta1 (π/2), n (elements per curve, 4), crank (0 or 1, 0).
DefineConstant[
  l1 = {0.3, Name "l1"},
  l2 = {0.6, Name "l2"},
  theta1 = {Pi/2, Name "theta1"},
  n = {4, Name "n"},
  crank = {0, Name "crank"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(l1 > 0 && l1 < 1e12))
  Error("parameter l1 = %g: expected a crank length > 0 (m)", l1);
  Abort;
EndIf
If (!(l2 > 0 && l2 < 1e12))
  Error("parameter l2 = %g: expected a rod length > 0 (m)", l2);
  Abort;
EndIf
If (!(theta1 > -1e12 && theta1 < 1e12))
  Error("parameter theta1 = %g: expected a finite angle (rad)", theta1);
  Abort;
EndIf
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per link from 1 to 100000", n);
  Abort;
EndIf
If (!(crank == 0 || crank == 1))
  Error("parameter crank = %g: expected 0 or 1", crank);
  Abort;
EndIf
xh = l1*Cos(theta1);
yh = l1*Sin(theta1);
x3 = xh + Sqrt(l2^2 - (l1*Sin(theta1))^2);

Point(1) = {xh, yh, 0};
Point(2) = {0.5*(xh + x3), 0.5*yh, 0};
Point(3) = {x3, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Transfinite Curve{1, 2} = n + 1;
Physical Curve("rod") = {1, 2};
Physical Point("A") = {1};
Physical Point("mid") = {2};
Physical Point("B") = {3};

If (crank)
  Point(4) = {0, 0, 0};
  Point(5) = {xh, yh, 0};
  Line(3) = {4, 5};
  Transfinite Curve{3} = n + 1;
  Physical Curve("crank") = {3};
  Physical Point("O") = {4};
  Physical Point("H") = {5};
EndIf
