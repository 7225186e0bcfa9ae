// A block 2 m wide and 0.5 m tall resting on a rigid base, for the tests of an evolving normal
// traction (tests/normal.rs): its base the frictional contact ("base"), its top ("top") and
// sides ("left", "right") free. Structured 8 x 2 bilinear quadrilaterals. Written with Gmsh
// 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 block_on_base.geo -o block_on_base.msh
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 0.5, 0};
Point(4) = {0, 0.5, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 9;
Transfinite Curve {2, 4} = 3;
Transfinite Surface {1};
Recombine Surface {1};
Physical Surface("block") = {1};
Physical Curve("base") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
