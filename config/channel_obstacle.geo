// The mesh of config/channel_obstacle.msh: the channel [0, 3] x [0, 1] without the
// obstacle [0.75, 1.25] x [0.375, 0.625], as 17 quadrilaterals on a 6 x 3 grid.
// Regenerate: gmsh -2 -format msh22 config/channel_obstacle.geo -o config/channel_obstacle.msh
// anisodwr reads quadrilaterals only: every surface is transfinite with one cell per
// curve (Transfinite Curve = 2 nodes) and recombined into quads. For a free mesh, drop
// the Transfinite lines and keep "Recombine Surface" with Mesh.Algorithm = 8 and
// Mesh.RecombinationAlgorithm = 2 (or Mesh.SubdivisionAlgorithm = 1: all quads).
// Physical tags become boundary ids: 1 inflow, 2 outflow, 3 walls, 4 obstacle; the
// config names them in scene.dirichlet / scene.neumann / flux goals.
xs[] = {0, 0.375, 0.75, 1.25, 1.75, 2.375, 3};
ys[] = {0, 0.375, 0.625, 1};
nx = 7; ny = 4;
For j In {0 : ny - 1}
  For i In {0 : nx - 1}
    Point(1 + i + nx * j) = {xs[i], ys[j], 0};
  EndFor
EndFor
// horizontal curve (i, j) -> (i + 1, j): id 100 + i + nx j; vertical (i, j) -> (i, j + 1): 200 + i + nx j
For j In {0 : ny - 1}
  For i In {0 : nx - 2}
    Line(100 + i + nx * j) = {1 + i + nx * j, 2 + i + nx * j};
  EndFor
EndFor
For j In {0 : ny - 2}
  For i In {0 : nx - 1}
    Line(200 + i + nx * j) = {1 + i + nx * j, 1 + i + nx * (j + 1)};
  EndFor
EndFor
cells[] = {};
For j In {0 : ny - 2}
  For i In {0 : nx - 2}
    If (!(i == 2 && j == 1)) // the obstacle
      Curve Loop(1000 + i + nx * j) = {100 + i + nx * j, 201 + i + nx * j,
                                      -(100 + i + nx * (j + 1)), -(200 + i + nx * j)};
      Plane Surface(1000 + i + nx * j) = {1000 + i + nx * j};
      cells[] += {1000 + i + nx * j};
    EndIf
  EndFor
EndFor
Transfinite Curve {:} = 2;
Transfinite Surface {cells[]};
Recombine Surface {cells[]};

Physical Curve("inflow", 1) = {200, 207, 214};
Physical Curve("outflow", 2) = {206, 213, 220};
Physical Curve("walls", 3) = {100 : 105, 121 : 126};
Physical Curve("obstacle", 4) = {109, 116, 209, 210};
Physical Surface("channel", 10) = {cells[]};
