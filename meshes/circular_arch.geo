// circular_arch.geo — circular arch of radius R and opening angle alpha (degrees), symmetric about
// the y axis, centre at the origin, crown at (0, R); meshed with n equal 2-node elements per half.
// Units: m (any consistent length).
// Physical groups: line "arch"; points "left" (end at angle 90° + alpha/2), "right" (end at
// 90° − alpha/2), "crown" (0, R).
// Parameters (ONELAB, set from a scene's mesh.parameters or `gmsh -setnumber NAME VALUE`):
//   R      radius, default 100
//   alpha  opening angle in degrees, default 215 (DaDeppo & Schmidt 1975's deep arch), < 360
//   n      elements per half arch, default 20
DefineConstant[
  R = {100, Name "R"},
  alpha = {215, Name "alpha"},
  n = {20, Name "n"}
];
If (!(R > 0 && R < 1e12))
  Error("parameter R = %g: expected a radius > 0", R);
  Abort;
EndIf
If (!(alpha > 0 && alpha < 359))
  Error("parameter alpha = %g: expected an opening angle in degrees in (0, 359)", alpha);
  Abort;
EndIf
If (!(n >= 1 && n <= 100000 && n == Round(n)))
  Error("parameter n = %g: expected a whole number of elements per half from 1 to 100000", n);
  Abort;
EndIf

half = alpha / 2 * Pi / 180;
Point(1) = {0, 0, 0};
Point(2) = {R * Sin(half), R * Cos(half), 0};    // right end
Point(3) = {0, R, 0};                            // crown
Point(4) = {-R * Sin(half), R * Cos(half), 0};   // left end
// Each half is less than 180°, as gmsh's Circle needs.
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Transfinite Curve{1, 2} = n + 1;

Physical Curve("arch") = {1, 2};
Physical Point("right") = {2};
Physical Point("crown") = {3};
Physical Point("left") = {4};
