// The lower half of a cylinder of radius 1 m (centre (0, 1)) resting on a rigid flat base at
// y = 0, for Hertz's line contact (tests/normal.rs): its lower arc
// from -60 to +60 degrees is the frictional contact ("arc"), its flat top ("top") is moved
// by the tests, the rest of the arc ("sides") is free. Quadrilaterals of 5 mm near the
// bottom, growing to 0.1 m. Written with Gmsh 4.15.2 (`pip install gmsh==4.15.2`):
//   gmsh -2 -format msh41 half_cylinder.geo -o half_cylinder.msh
s = Sqrt(3) / 2;
Point(1) = {0, 1, 0};      // the centre
Point(2) = {0, 0, 0};      // the bottom
Point(3) = {s, 0.5, 0};
Point(4) = {1, 1, 0};
Point(5) = {-1, 1, 0};
Point(6) = {-s, 0.5, 0};
Circle(1) = {6, 1, 2};
Circle(2) = {2, 1, 3};
Circle(3) = {3, 1, 4};
Line(4) = {4, 5};
Circle(5) = {5, 1, 6};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {2};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.005;
Field[2].SizeMax = 0.1;
Field[2].DistMin = 0.2;
Field[2].DistMax = 0.8;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 8;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;
Physical Surface("cylinder") = {1};
Physical Curve("arc") = {1, 2};
Physical Curve("sides") = {3, 5};
Physical Curve("top") = {4};
