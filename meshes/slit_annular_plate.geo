// slit_annular_plate.geo — the slit annular plate of Sze, Liu & Lo (2004), Sec. 3.3: inner radius
// Ri = 6, outer Ro = 10, in the x-y plane, cut along the positive x-axis; the edge at θ = 0 is
// loaded, the edge at θ = 2π (the same line, other side of the slit) is clamped. nr × nt
// quadrilaterals (10 × 80 in the paper's reference solution). Units: m.
// Physical groups: surface "plate"; curves "loaded" (θ = 0), "clamped" (θ = 2π); points "A"
// (r = Ri on the loaded edge) and "B" (r = Ro on the loaded edge).
// Parameters: Ri (6 m), Ro (10 m), nr (10), nt (80, a multiple of 4), quads (1 or 0).
DefineConstant[
  Ri = {6, Name "Ri"},
  Ro = {10, Name "Ro"},
  nr = {10, Name "nr"},
  nt = {80, Name "nt"},
  quads = {1, Name "quads"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(Ri > 0 && Ri < 1e12))
  Error("parameter Ri = %g: expected a inner radius > 0 (m)", Ri);
  Abort;
EndIf
If (!(Ro > 0 && Ro < 1e12))
  Error("parameter Ro = %g: expected a outer radius > 0 (m)", Ro);
  Abort;
EndIf
If (!(nr >= 1 && nr <= 10000 && nr == Round(nr)))
  Error("parameter nr = %g: expected a whole number of radial elements from 1 to 10000", nr);
  Abort;
EndIf
If (!(nt >= 1 && nt <= 10000 && nt == Round(nt)))
  Error("parameter nt = %g: expected a whole number of circumferential elements from 1 to 10000", nt);
  Abort;
EndIf
If (!(quads == 0 || quads == 1))
  Error("parameter quads = %g: expected 0 or 1", quads);
  Abort;
EndIf
If (!(nr * nt <= 10000000))
  Error("parameters give %g elements: expected at most 1e+07", nr * nt);
  Abort;
EndIf

Point(1) = {0, 0, 0};                 // centre of the arcs
Point(2) = {Ri, 0, 0};                // A, loaded edge
Point(3) = {Ro, 0, 0};                // B, loaded edge
Point(4) = {0, Ro, 0};
Point(5) = {-Ro, 0, 0};
Point(6) = {0, -Ro, 0};
Point(7) = {Ro, 0, 0};                // the clamped edge's outer end (a distinct point at B)
Point(8) = {Ri, 0, 0};                // ... and inner end (at A)
Point(9) = {0, -Ri, 0};
Point(10) = {-Ri, 0, 0};
Point(11) = {0, Ri, 0};
Line(1) = {2, 3};                     // loaded edge
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6};
Circle(5) = {6, 1, 7};
Line(6) = {7, 8};                     // clamped edge
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 10};
Circle(9) = {10, 1, 11};
Circle(10) = {11, 1, 2};
// Counter-clockwise about +z: out along the loaded edge, round the outer circle, in along the
// clamped edge, back round the inner circle.
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
Plane Surface(1) = {1};
Transfinite Curve{1, 6} = nr + 1;
Transfinite Curve{2, 3, 4, 5, 7, 8, 9, 10} = nt / 4 + 1;
Transfinite Surface{1} = {2, 3, 7, 8};
If (quads)
  Recombine Surface{1};
EndIf

Physical Surface("plate") = {1};
Physical Curve("loaded") = {1};
Physical Curve("clamped") = {6};
Physical Point("A") = {2};
Physical Point("B") = {3};
