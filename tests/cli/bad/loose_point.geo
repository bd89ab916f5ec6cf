// A beam with a named point that is not on it (for tests/cli/bad/unconnected_point_3d.yaml).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {0.5, 0.5, 0};
Line(1) = {1, 2};
Transfinite Curve{1} = 3;
Physical Curve("beam") = {1};
Physical Point("root") = {1};
Physical Point("loose") = {3};
