// sign_post.geo — a post and the sign it carries: a vertical line from (0, 0, 0) to (0, 0, H)
// (n_post 2-node elements) and a rectangle [0, a] × [H, H + b] in the x-z plane (n_sign × n_sign
// transfinite quadrilaterals) whose corner (0, 0, H) is the post's top: the two share that mesh
// node and nothing else. Units: m.
// Physical groups: curve "post", surface "sign"; points "base" (0, 0, 0), "top" (0, 0, H, the
// shared corner) and "far_corner" (a, 0, H + b).
// Parameters: H (1 m), a (0.4 m), b (0.3 m), n_post (10), n_sign (4).
DefineConstant[
  H = {1, Name "H"},
  a = {0.4, Name "a"},
  b = {0.3, Name "b"},
  n_post = {10, Name "n_post"},
  n_sign = {4, Name "n_sign"}
];
// Parameter ranges: a value outside them is a gmsh error naming it, before any loop or mesh runs
// (meshes/README.md).
If (!(H > 0 && H < 1e12 && a > 0 && a < 1e12 && b > 0 && b < 1e12))
  Error("parameters H = %g, a = %g, b = %g: expected lengths > 0 (m)", H, a, b);
  Abort;
EndIf
If (!(n_post >= 1 && n_post <= 100000 && n_post == Round(n_post) && n_sign >= 1 && n_sign <= 10000 && n_sign == Round(n_sign)))
  Error("parameters n_post = %g, n_sign = %g: expected whole numbers of elements (1 to 100000, 1 to 10000)", n_post, n_sign);
  Abort;
EndIf

Point(1) = {0, 0, 0};
Point(2) = {0, 0, H};
Point(3) = {a, 0, H};
Point(4) = {a, 0, H + b};
Point(5) = {0, 0, H + b};
Line(1) = {1, 2};                                  // the post
Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 2};
Curve Loop(1) = {2, 3, 4, 5};
Plane Surface(1) = {1};
Transfinite Curve{1} = n_post + 1;
Transfinite Curve{2:5} = n_sign + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Curve("post") = {1};
Physical Surface("sign") = {1};
Physical Point("base") = {1};
Physical Point("top") = {2};
Physical Point("far_corner") = {4};
