// Two separate unit squares: "near" (x in [0, 1]) and "far" (x in [2, 3]), and the far square's
// edge "far" — for the CLI test shell_edge_load_foreign_nodes.yaml.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Point(5) = {2, 0, 0}; Point(6) = {3, 0, 0}; Point(7) = {3, 1, 0}; Point(8) = {2, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface("near") = {1};
Physical Surface("other") = {2};
Physical Curve("far") = {6};
