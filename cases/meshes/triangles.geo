// A 2 m x 1 m rectangle [0, 2] x [0, 1] cut into 4 triangles, whose surface, bottom curve and
// corner point are each in two physical groups (one of them unnamed). Written with Gmsh 4.15.2
// (`pip install gmsh==4.15.2`) by scripts/paper_block_meshes.py: as triangles_v2.msh (MSH 2.2
// ASCII, where an element in two groups is written twice) and as triangles_parametric.msh
// (MSH 4.1 ASCII with Mesh.SaveParametric = 1: the nodes inside curves carry their parameter).
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 3;
Transfinite Curve {2, 4} = 2;
Transfinite Surface {1};
Physical Surface("body") = {1};
Physical Surface(7) = {1};
Physical Curve("bottom") = {1};
Physical Curve("base") = {1};
Physical Point("origin") = {1};
Physical Point("also origin") = {1};
