// Source of the .msh files beside it (committed, so the tests need no gmsh):
//   gmsh -2 -save_all -format msh41 three_volumes.geo -o three_volumes_41.msh      (and -bin)
//   gmsh -2 -save_all -format msh22 three_volumes.geo -o three_volumes_22.msh      (and -bin)
// Silicon (physical 11) with a cube-shaped inclusion (no physical group: number = its entity
// tag), oxide (physical 12) on top; the silicon/oxide interface is physical surface 20.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 0.5};
Box(3) = {0.4, 0.4, 0.4, 0.2, 0.2, 0.2};
BooleanFragments{ Volume{1, 2, 3}; Delete; }{}
Physical Volume("silicon", 11) = Volume In BoundingBox{-0.1, -0.1, -0.1, 1.1, 1.1, 1.1};
Physical Volume("silicon", 11) -= Volume In BoundingBox{0.3, 0.3, 0.3, 0.7, 0.7, 0.7};
Physical Volume("oxide", 12) = Volume In BoundingBox{-0.1, -0.1, 0.9, 1.1, 1.1, 1.6};
Physical Surface("interface", 20) = Surface In BoundingBox{-0.1, -0.1, 0.9, 1.1, 1.1, 1.1};
Mesh.MeshSizeMax = 0.5;
