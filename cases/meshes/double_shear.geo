// A double-direct-shear sample, as rock-friction laboratories test gouge: a block 2 m wide and
// 6 m tall held between two fixed side plates, its two sides the frictional contacts ("left",
// "right"), its top pushed down by a piston 1.5 m wide ("piston"; the top's 0.25 m beside it
// free, so that no node is both pushed and on a contact), its bottom free. Structured 8 x 24
// bilinear quadrilaterals. Written with Gmsh 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 double_shear.geo -o double_shear.msh
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 6, 0};
Point(4) = {1.75, 6, 0};
Point(5) = {0.25, 6, 0};
Point(6) = {0, 6, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Transfinite Curve {1} = 9;
Transfinite Curve {3, 5} = 2;
Transfinite Curve {4} = 7;
Transfinite Curve {2, 6} = 25;
Transfinite Surface {1} = {1, 2, 3, 6};
Recombine Surface {1};
Physical Surface("sample") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("piston") = {4};
Physical Curve("left") = {6};
