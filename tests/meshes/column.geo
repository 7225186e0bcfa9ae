// A column 1 m wide and 10 m tall resting on its base, for the test of a body under its own
// weight (tests/gravity.rs): its base the frictional contact ("base"), its sides on rollers
// ("left", "right"), its top free ("top"). Structured 2 x 20 bilinear quadrilaterals. Written
// with Gmsh 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 column.geo -o column.msh
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 10, 0};
Point(4) = {0, 10, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 3;
Transfinite Curve {2, 4} = 21;
Transfinite Surface {1};
Recombine Surface {1};
Physical Surface("column") = {1};
Physical Curve("base") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
