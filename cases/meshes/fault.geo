// A plate on a fault dipping 30 degrees into the ground: the fault is the plate's bottom, 10 m
// long from its shallow end at (0, 0) down to (8.66, -5) (y upwards), and the plate is 1 m
// thick across it. The fault ("fault") is the frictional contact with the rigid footwall below;
// the plate's top face ("top"), parallel to the fault, is the far boundary that drives it; its
// up-dip and down-dip ends ("updip", "downdip") are free. Structured 20 x 2 bilinear
// quadrilaterals of 0.5 m. Written with Gmsh 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 fault.geo -o fault.msh
c = Cos(Pi / 6);
s = Sin(Pi / 6);
Point(1) = {0, 0, 0};
Point(2) = {10 * c, -10 * s, 0};
Point(3) = {10 * c + s, -10 * s + c, 0};
Point(4) = {s, c, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 21;
Transfinite Curve {2, 4} = 3;
Transfinite Surface {1};
Recombine Surface {1};
Physical Surface("plate") = {1};
Physical Curve("fault") = {1};
Physical Curve("downdip") = {2};
Physical Curve("top") = {3};
Physical Curve("updip") = {4};
