// A 10 m x 1 m block of two layers, for the series-stiffness test of tests/mesh_cases.rs: "soft"
// below y = 0.4 m, "stiff" above, in unstructured triangles of 0.25 m. Written with Gmsh 4.15.2:
//   gmsh -2 -format msh41 two_layers.geo -o two_layers.msh
h = 0.25;
Point(1) = {0, 0, 0, h};
Point(2) = {10, 0, 0, h};
Point(3) = {10, 0.4, 0, h};
Point(4) = {0, 0.4, 0, h};
Point(5) = {10, 1, 0, h};
Point(6) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};
Physical Surface("soft") = {1};
Physical Surface("stiff") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
Physical Curve("sides") = {4, 7, 2, 5};
