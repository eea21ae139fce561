#!/usr/bin/python3
"""Writes the .vtu background meshes of tests/sizing (run once, output committed):
the cube [-0.01, 0.05]^3 as 6 tetrahedra (Kuhn) with the point field size = 0.003 + 0.2 (x + 0.01),
by meshio in three encodings (ascii; base64 zlib-compressed, UInt32 headers, meshio's default;
base64 uncompressed with UInt64 headers), a hexahedron version (refused by the reader), and
the square [-0.01, 0.05]^2 as 2 triangles with the same field (2D)."""
import meshio
import numpy as np

lo, hi = -0.01, 0.05
pts = np.array([[hi if i & 1 else lo, hi if i & 2 else lo, hi if i & 4 else lo] for i in range(8)])
size = 0.003 + 0.2 * (pts[:, 0] + 0.01)
kuhn = [[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]]
# a triangle on the surface too: lower-dimensional cells are skipped
m = meshio.Mesh(pts, [("tetra", np.array(kuhn)), ("triangle", np.array([[0, 1, 3]]))],
                point_data={"size": size, "other": np.arange(8.0)})
meshio.write("bg_ascii.vtu", m, binary=False)
meshio.write("bg_zlib.vtu", m)
meshio.write("bg_raw64.vtu", m, compression=None, header_type="UInt64")
hexa = meshio.Mesh(pts, [("hexahedron", np.array([[0, 1, 3, 2, 4, 5, 7, 6]]))], point_data={"size": size})
meshio.write("bg_hex.vtu", hexa, binary=False)
p2 = np.array([[lo, lo], [hi, lo], [lo, hi], [hi, hi]])
m2 = meshio.Mesh(p2, [("triangle", np.array([[0, 1, 3], [0, 3, 2]]))], point_data={"size": 0.003 + 0.2 * (p2[:, 0] + 0.01)})
meshio.write("bg_2d.vtu", m2)
