// cylindrical_roof.geo — shallow cylindrical panel of radius R, length L along y and half-angle
// theta (rad), the hinged roof of Sabir & Lock (1972) (Sze, Liu & Lo 2004, Sec. 3.7 uses the same
// roof): the axis is parallel to y at (0, ·, −R cos theta), so the straight edges (x = ±R sin theta)
// lie in z = 0 and the crown at x = 0 rises to R(1 − cos theta). Four transfinite patches meet at
// the centre, n × n quadrilaterals each (2n × 2n in all). Units: mm.
// Physical groups: surface "roof"; curves "straight" (the two edges x = ±R sin theta, along y),
// "curved" (y = ±L/2); points "center" (0, 0, R(1 − cos theta)), "edge_mid" (0, L/2, R(1 − cos theta)).
// Parameters: R (2540), L (508), theta (0.1 rad), n (4 elements per patch side), quads (1).
DefineConstant[
  R = {2540, Name "R"},
  L = {508, Name "L"},
  theta = {0.1, Name "theta"},
  n = {4, Name "n"},
  quads = {1, Name "quads"}
];
If (!(R > 0 && R < 1e12 && L > 0 && L < 1e12))
  Error("parameters R = %g, L = %g: expected lengths > 0", R, L);
  Abort;
EndIf
If (!(theta > 0 && theta < 1.5))
  Error("parameter theta = %g: expected a half-angle in (0, 1.5) rad", theta);
  Abort;
EndIf
If (!(n >= 1 && n <= 2000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per patch side from 1 to 2000", n);
  Abort;
EndIf
If (!(quads == 0 || quads == 1))
  Error("parameter quads = %g: expected 0 or 1", quads);
  Abort;
EndIf

zc = -R * Cos(theta);  // the axis
s = R * Sin(theta);
h = R - R * Cos(theta);
// Points p[i][j]: i over the angle (−theta, 0, theta), j over y (−L/2, 0, L/2); centres c[j].
For j In {0:2}
  y = -L / 2 + j * L / 2;
  c[j] = newp; Point(c[j]) = {0, y, zc};
  p[0 + 3 * j] = newp; Point(p[0 + 3 * j]) = {-s, y, 0};
  p[1 + 3 * j] = newp; Point(p[1 + 3 * j]) = {0, y, h};
  p[2 + 3 * j] = newp; Point(p[2 + 3 * j]) = {s, y, 0};
EndFor
// Arcs a[i + 2j] from angle index i to i + 1 at y index j; lines b[i + 3j] along y from j to j + 1.
For j In {0:2}
  For i In {0:1}
    a[i + 2 * j] = newc; Circle(a[i + 2 * j]) = {p[i + 3 * j], c[j], p[i + 1 + 3 * j]};
  EndFor
EndFor
For j In {0:1}
  For i In {0:2}
    b[i + 3 * j] = newc; Line(b[i + 3 * j]) = {p[i + 3 * j], p[i + 3 * (j + 1)]};
  EndFor
EndFor
k = 0;
For j In {0:1}
  For i In {0:1}
    cl = newll; Curve Loop(cl) = {a[i + 2 * j], b[i + 1 + 3 * j], -a[i + 2 * (j + 1)], -b[i + 3 * j]};
    sf[k] = news; Surface(sf[k]) = {cl};
    k += 1;
  EndFor
EndFor
Transfinite Curve{a[], b[]} = n + 1;
Transfinite Surface{sf[]};
If (quads)
  Recombine Surface{sf[]};
EndIf

Physical Surface("roof") = {sf[]};
Physical Curve("straight") = {b[0], b[3], b[2], b[5]};
Physical Curve("curved") = {a[0], a[1], a[4], a[5]};
Physical Point("center") = {p[4]};
Physical Point("edge_mid") = {p[7]};
