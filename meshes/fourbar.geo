// fourbar.geo — the spatial four-bar mechanism with flexible links of Bauchau et al. (2016,
// Multibody Syst. Dyn. 37, "Validation of flexible multibody dynamics beam formulations using
// benchmark problems"), in its initial configuration in the x-y plane: a parallelogram
// A (0, 0, 0) – B (0, 0.12, 0) – C (0.24, 0.12, 0) – D (0.24, 0, 0).
// Units: m.
// Each bar has its own end points (coincident points are separate nodes), so that the bars are
// joined only by the scene's revolute joints.
// Physical groups: curves "bar1" (crank A–B), "bar2" (coupler B–C), "bar3" (follower C–D);
// points "A", "B1" (end of bar1), "B2" (start of bar2), "C2" (end of bar2), "C3" (start of bar3), "D".
// Parameters (ONELAB): n  elements per bar, default 8.
DefineConstant[ n = {8, Name "n"} ];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per link from 1 to 100000", n);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {0, 0.12, 0};
Point(3) = {0, 0.12, 0};
Point(4) = {0.24, 0.12, 0};
Point(5) = {0.24, 0.12, 0};
Point(6) = {0.24, 0, 0};
Line(1) = {1, 2};
Line(2) = {3, 4};
Line(3) = {5, 6};
Transfinite Curve{1, 2, 3} = n + 1;

Physical Curve("bar1") = {1};
Physical Curve("bar2") = {2};
Physical Curve("bar3") = {3};
Physical Point("A") = {1};
Physical Point("B1") = {2};
Physical Point("B2") = {3};
Physical Point("C2") = {4};
Physical Point("C3") = {5};
Physical Point("D") = {6};
