// The paper's block (10 m x 1 m, 10 x 1 quadrilaterals) rotated by 30 degrees about the origin,
// for the rotation test of tests/mesh_cases.rs. Written with Gmsh 4.15.2:
//   gmsh -2 -format msh41 block_rotated.geo -o block_rotated.msh
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 11;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
Recombine Surface{1};
Rotate {{0, 0, 1}, {0, 0, 0}, Pi/6} { Surface{1}; }
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
