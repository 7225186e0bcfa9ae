// A pile shaft in soil, axisymmetric: the soil around a rigid shaft of radius R = 0.3 m and
// embedded length L = 10 m, meshed in its half-plane r = x >= 0 (x the radius), z = y upwards
// with the ground surface at z = 0. The soil spans r from the axis to 20 R = 6 m and z from
// -1.5 L to 0, less the shaft (r < R, z > -L): its face along the shaft is the frictional
// contact ("shaft"), its base ("base") and far face ("far") are fixed, the ground surface
// ("surface") and the face under the shaft's tip ("tip") are free (a pile pulled out leaves
// its tip), and u_r = 0 on the axis below the tip. Structured bilinear quadrilaterals in three
// blocks: 0.25 m along the shaft, graded in r from 0.05 m at the shaft to 1.1 m at the far face,
// 0.1 m across the tip. Written with Gmsh 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 pile.geo -o pile.msh
R = 0.3;
L = 10;
H = 15;
Point(1) = {0, -H, 0};
Point(2) = {R, -H, 0};
Point(3) = {20 * R, -H, 0};
Point(4) = {20 * R, -L, 0};
Point(5) = {20 * R, 0, 0};
Point(6) = {R, 0, 0};
Point(7) = {R, -L, 0};
Point(8) = {0, -L, 0};
Line(1) = {1, 2};   // base under the tip
Line(2) = {2, 3};   // base beside it
Line(3) = {3, 4};   // far face, below the tip's level
Line(4) = {4, 5};   // far face, along the shaft
Line(5) = {5, 6};   // ground surface
Line(6) = {6, 7};   // the shaft
Line(7) = {7, 8};   // under the tip
Line(8) = {8, 1};   // the axis
Line(9) = {7, 4};   // inside: the tip's level
Line(10) = {7, 2};  // inside: below the shaft's face
Curve Loop(1) = {9, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, -9, 10};
Plane Surface(2) = {2};
Curve Loop(3) = {1, -10, 7, 8};
Plane Surface(3) = {3};
Transfinite Curve {9, 2} = 17 Using Progression 1.21;
Transfinite Curve {5} = 17 Using Progression 1 / 1.21;
Transfinite Curve {4, 6} = 41;
Transfinite Curve {3, 10, 8} = 11;
Transfinite Curve {1, 7} = 4;
Transfinite Surface {1, 2, 3};
Recombine Surface {1, 2, 3};
Physical Surface("soil") = {1, 2, 3};
Physical Curve("base") = {1, 2};
Physical Curve("far") = {3, 4};
Physical Curve("surface") = {5};
Physical Curve("shaft") = {6};
Physical Curve("tip") = {7};
