// The paper's block (10 m x 1 m) in unstructured triangles of size h (default 0.5 m), for the
// stuck-limit convergence of tests/mesh_cases.rs. Written with Gmsh 4.15.2:
//   gmsh -2 -format msh41 -setnumber h 0.5 block_triangles.geo -o block_triangles_h0.5.msh
If (!Exists(h))
  h = 0.5;
EndIf
Point(1) = {0, 0, 0, h};
Point(2) = {10, 0, 0, h};
Point(3) = {10, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.Algorithm = 5; // Delaunay
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
