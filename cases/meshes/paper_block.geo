// The paper's block (Fig. 6): a 10 m x 1 m rectangle [0, 10] x [0, 1] meshed with 10 x 1
// structured bilinear quadrilaterals (transfinite + recombine). Written with Gmsh 4.15.2
// (`pip install gmsh==4.15.2`) by scripts/paper_block_meshes.py, which writes every form.
//
// Each side is made of one curve per element edge, so that every node is a point given here at
// integer coordinates: the node coordinates are then exact in every form. (With one curve per
// side, Gmsh's 1-D mesher places the inner nodes with a round-off of ~1e-11 m, which its ASCII
// forms print with 16 significant digits and so do not give back the binary form's doubles.)
//
// Physical groups: surface "body"; curves "bottom" (y = 0), "right" (x = 10), "top" (y = 1),
// "left" (x = 0).
For i In {0:10}
  Point(1 + i) = {i, 0, 0};       // bottom, from x = 0 to x = 10
  Point(12 + i) = {10 - i, 1, 0}; // top, from x = 10 to x = 0
EndFor
For i In {0:9}
  Line(1 + i) = {1 + i, 2 + i};
  Line(12 + i) = {12 + i, 13 + i};
EndFor
Line(11) = {11, 12};
Line(22) = {22, 1};
Curve Loop(1) = {1:22};
Plane Surface(1) = {1};
Transfinite Curve {1:22} = 2;
Transfinite Surface {1} = {1, 11, 12, 22};
Recombine Surface {1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1:10};
Physical Curve("right") = {11};
Physical Curve("top") = {12:21};
Physical Curve("left") = {22};
