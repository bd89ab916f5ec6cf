// gridshell.geo — a square grid of n × n continuous laths (beams) in the x-y plane, the kind of
// grid an elastic gridshell is formed from: n laths along x (y = i·d) and n along y (x = j·d),
// d = L/(n − 1), crossing at n² points. At each crossing the x lath and the y lath have their own
// point (coincident points are separate nodes), so that the scene joins them by a swivel (revolute)
// joint rather than merging them. Each lath has n − 1 bays of k elements.
// Units: m.
// Physical groups: curves "xlaths", "ylaths"; points "supports" (both ends of every x lath, 2n
// points), "center" (the x-lath point at crossing (⌊n/2⌋, ⌊n/2⌋)).
// Parameters (ONELAB): n  laths per direction (default 8), k  elements per bay (default 4),
//                      L  side of the grid (default 10 m).
// Size: 2n((n − 1)k + 1) nodes, i.e. 12n((n − 1)k + 1) coordinates; with the scene's n² swivels
// (5 equations each) and 2n supports (3 each), n = 48, k = 4 gives 1.2·10⁵ unknowns.
DefineConstant[ n = {8, Name "n"}, k = {4, Name "k"}, L = {10, Name "L"} ];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (n = 1e19 made gmsh loop for ever: found by tests/fuzz; meshes/README.md).
If (!(n >= 2 && n <= 1024 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of laths per direction from 2 to 1024", n);
  Abort;
EndIf
If (!(k >= 1 && k <= 1000 && k == Round(k)))
  Error("parameter k = %g: expected a whole number of elements per bay from 1 to 1000", k);
  Abort;
EndIf
If (!(L > 0 && L < 1e12))
  Error("parameter L = %g: expected a side > 0 (m)", L);
  Abort;
EndIf
If (!(2 * n * ((n - 1) * k + 1) <= 10000000))
  Error("parameters give %g nodes: expected at most 1e+07", 2 * n * ((n - 1) * k + 1));
  Abort;
EndIf
d = L / (n - 1);

// Points: x laths first (row i, column j), then y laths.
For i In {0 : n - 1}
  For j In {0 : n - 1}
    px[i * n + j] = newp; Point(px[i * n + j]) = {j * d, i * d, 0};
  EndFor
EndFor
For j In {0 : n - 1}
  For i In {0 : n - 1}
    py[j * n + i] = newp; Point(py[j * n + i]) = {j * d, i * d, 0};
  EndFor
EndFor

xl[] = {};
yl[] = {};
For i In {0 : n - 1}
  For j In {0 : n - 2}
    c = newl; Line(c) = {px[i * n + j], px[i * n + j + 1]}; xl[] += c;
    c = newl; Line(c) = {py[i * n + j], py[i * n + j + 1]}; yl[] += c;
  EndFor
EndFor
Transfinite Curve{xl[], yl[]} = k + 1;

Physical Curve("xlaths") = {xl[]};
Physical Curve("ylaths") = {yl[]};
ends[] = {};
For i In {0 : n - 1}
  ends[] += {px[i * n], px[i * n + n - 1]};
EndFor
Physical Point("supports") = {ends[]};
m = Floor(n / 2);
Physical Point("center") = {px[m * n + m]};
