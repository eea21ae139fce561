#!/usr/bin/env python3
"""The Python module, as a device-simulation script uses it (run with /usr/bin/python3, the
interpreter of Debian's numpy and meshio; PYTHONPATH = the build's python/ folder).

usage: test_gsse.py GSSE_MESH SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np

import gsse

failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += not ok


def tri_area(p, t):
    return np.linalg.norm(np.cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]])) / 2


def main():
    mesh, src = sys.argv[1], sys.argv[2]
    mosfet = os.path.join(src, "examples", "mosfet.poly")
    with tempfile.TemporaryDirectory(prefix="gsse_py_") as work:
        # 1. a file, as gsse-mesh meshes it
        m = gsse.mesh_file(mosfet, size=0.1, threads=2, verify=True)
        stats = os.path.join(work, "s.json")
        subprocess.run([mesh, mosfet, "--size", "0.1", "--quiet", "--stats", stats], check=True)
        s = json.load(open(stats))
        check(m.points.shape == (s["points"], 3) and m.cells.shape == (sum(x["cells"] for x in s["segments"]), 4),
              f"mesh_file: {m.points.shape[0]} points, {m.cells.shape[0]} tetrahedra, as gsse-mesh")
        check([n for _, n in m.segments] == [x["name"] for x in s["segments"]] and len(m.cell_segments) == len(m.cells),
              f"segments {m.segments[:3]}..., one number per cell")
        check(m.steiner == s["steiner"] and set(m.times) >= {"conform", "mesh"}, f"steiner {m.steiner}, stage times {sorted(m.times)}")
        # 1b. boundary faces: without a size, faces that are Delaunay but not Gabriel are kept;
        # gabriel=True (--gabriel) keeps every equatorial ball empty, with more points
        lo, hi = m.points.min(axis=0), m.points.max(axis=0)
        cloud = lo + (hi - lo) * np.random.default_rng(3).uniform(0.05, 0.95, (2000, 3))
        d = gsse.mesh_file(mosfet, threads=2, verify=True, cloud=cloud)
        g = gsse.mesh_file(mosfet, threads=2, verify=True, cloud=cloud, gabriel=True)
        cloud_node = os.path.join(work, "cloud.node")
        with open(cloud_node, "w") as f:
            f.write(f"{len(cloud)} 3 0 0\n" + "".join(f"{i + 1} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in enumerate(cloud)))
        subprocess.run([mesh, mosfet, "--cloud", cloud_node, "--gabriel", "--quiet", "--stats", stats], check=True)
        s = json.load(open(stats))
        check(d.steiner < g.steiner and g.steiner == s["steiner"] and s["boundary_faces"] == "gabriel",
              f"gabriel=False: {d.steiner} Steiner points, gabriel=True: {g.steiner}, as gsse-mesh --gabriel")
        # 2. arrays: a unit cube, bottom facet marker 1, top 2 (named), one region
        P = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
        F = [[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
        c = gsse.mesh(P, F, markers=[1, 2, 0, 0, 0, 0], regions=[(0.5, 0.5, 0.5, 3, "silicon")],
                      marker_names={2: "top"}, size=0.25, verify=True)
        faces, markers, sides = c.faces
        top = faces[markers == 2]
        area = sum(tri_area(c.points, t) for t in top)
        check(abs(area - 1) < 1e-12 and np.all(c.points[top.ravel(), 2] == 1.0),
              f"arrays: {len(top)} faces with marker 2, area {area:.15g}, all at z = 1")
        check(c.segments == [(3, "silicon")] and c.marker_names == {2: "top"} and set(sides[:, 1]) == {0},
              f"region {c.segments}, names {c.marker_names}, every face on the outside")
        vol = sum(abs(np.linalg.det(c.points[t[1:]] - c.points[t[0]])) / 6 for t in c.cells)
        check(abs(vol - 1) < 1e-12, f"tetrahedra fill the cube: volume {vol:.15g}")
        # 3. meshio
        mm = c.to_meshio()
        check([b.type for b in mm.cells] == ["tetra", "triangle"] and len(mm.cell_data["marker"][1]) == len(faces),
              f"to_meshio: {[(b.type, len(b.data)) for b in mm.cells]}, cell data {sorted(mm.cell_data)}")
        # 4. writers
        out = os.path.join(work, "cube.msh")
        c.write(out, msh="2.2")
        check(open(out).read().split("\n")[1] == "2.2 0 8" and '"top"' in open(out).read(), "write .msh 2.2 with the named group")
        # 5. 2D
        q = gsse.mesh(np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]),
                      markers=[5, 0, 0, 0], size=0.2)
        e, mk, _ = q.faces
        length = sum(np.linalg.norm(q.points[a] - q.points[b]) for a, b in e[mk == 5])
        check(q.dimension == 2 and abs(length - 1) < 1e-12, f"2D: {len(q.cells)} triangles, marker 5 on edges of length {length:.15g}")
        # 6. errors
        for what, f, kind, word in [("a missing file", lambda: gsse.mesh_file(os.path.join(work, "none.poly")), RuntimeError, "none.poly"),
                                    ("threads=0", lambda: gsse.mesh(P, F, threads=0), ValueError, "threads"),
                                    ("a facet index out of range", lambda: gsse.mesh(P, [[0, 1, 99]]), ValueError, "99")]:
            try:
                f()
                check(False, f"{what}: no error")
            except kind as x:
                check(word in str(x), f"{what}: {kind.__name__}: {x}")
        # 7. the GIL is released while meshing: this thread keeps counting meanwhile
        done, counted = [], [0]
        t = threading.Thread(target=lambda: done.append(gsse.mesh_file(mosfet, size=0.03)))
        t.start()
        time.sleep(0.01)
        n = 0
        while t.is_alive():
            n += 1
        t.join()
        check(bool(done) and n > 10000, f"GIL released: {n} loop turns in Python while a mesh of {len(done[0].cells)} tetrahedra was made")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
