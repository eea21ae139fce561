#!/usr/bin/env python3
"""Facet markers through gsse-mesh into every output format, checked by readers that are not ours.

The bundled MOSFET (3D) and its 2D section get marker 77 on their first facet (segment) and 78 on
the second, named in the sidecar ({"facets": {"77": "drain_contact", ...}}). After meshing with
--size, in each format the faces carrying marker 77 must cover exactly that input facet: their
areas (2D: lengths) sum to the facet's, and every one of their vertices lies in its plane (line).
- .node/.face (.edge): the marker column (plain text, read here);
- .msh 4.1 and 2.2 through Gmsh's own reader (python3-gmsh) and meshio: the physical group named
  "drain_contact", the volume groups named after the segments, and interface groups
  "<a>:<b>" holding exactly the faces shared by cells of segments a and b (found by brute force
  from the cells); 2.2's header is "2.2 0 8", as devsim's reader requires;
- .vtu: meshio reads BASE.boundary.vtu, cell data "marker".
And a Gmsh model whose top surface is a named physical group keeps the group, named, in the output.

usage: markers.py GSSE_MESH SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile

try:
    import gmsh
    import meshio
    import numpy as np
except ImportError as e:
    print(f"SKIPPED: python3-gmsh, meshio or numpy not available ({e})")
    sys.exit(0)

failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += not ok


def marked_input(src, dst, dim):
    """Copies the example with markers 77 and 78 on its first two facets (segments)."""
    lines = open(src).read().split("\n")
    data = [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith("#")]
    npts = int(lines[data[0]].split()[0])
    head = data[npts + 1]  # facet (segment) count line
    pts = [list(map(float, lines[data[1 + k]].split()[1:1 + dim])) for k in range(npts)]
    if dim == 3:
        i, corners = data.index(head) + 1, []
        for f in range(2):
            fl = lines[data[i]].split()
            lines[data[i]] = f"{fl[0]} {fl[1] if len(fl) > 1 else 0} {77 + f}"
            poly = [int(v) - 1 for v in lines[data[i + 1]].split()[1:]]
            corners.append(poly)
            i += 1 + int(fl[0])
    else:
        corners = []
        for f in range(2):
            k = data[data.index(head) + 1 + f]
            sl = lines[k].split()
            lines[k] = f"{sl[0]} {sl[1]} {sl[2]} {77 + f}"
            corners.append([int(sl[1]) - 1, int(sl[2]) - 1])
    open(dst, "w").write("\n".join(lines))
    return np.array(pts), corners


def facet_measure(pts, poly):
    """Area of a planar polygon (3D) or length of a segment (2D)."""
    p = pts[poly]
    if p.shape[1] == 2:
        return float(np.linalg.norm(p[1] - p[0]))
    s = np.zeros(3)
    for k in range(len(p)):
        s += np.cross(p[k], p[(k + 1) % len(p)])
    return float(np.linalg.norm(s) / 2)


def face_measure(x):
    if len(x) == 2:
        return float(np.linalg.norm(x[1] - x[0]))
    return float(np.linalg.norm(np.cross(x[1] - x[0], x[2] - x[0])) / 2)


def on_facet(pts, poly, x):
    """Every point of x in the facet's plane (3D: the example's facets are axis-aligned, so
    within 1e-12 of it) or on the segment's line (2D)."""
    p = pts[poly]
    if p.shape[1] == 2:
        d = p[1] - p[0]
        return all(abs(d[0] * (q[1] - p[0][1]) - d[1] * (q[0] - p[0][0])) <= 1e-12 for q in x)
    n = np.cross(p[1] - p[0], p[2] - p[0])
    n = n / np.linalg.norm(n)
    return all(abs(np.dot(q - p[0], n)) <= 1e-12 for q in x)


def covers(pts, poly, xs, what):
    want = facet_measure(pts, poly)
    got = sum(face_measure(x) for x in xs)
    check(len(xs) > 1 and abs(got - want) <= 1e-9 * want and all(on_facet(pts, poly, x) for x in xs),
          f"{what}: {len(xs)} faces, measure {got:.12g} of the facet's {want:.12g}, all in its plane")


def interfaces_by_brute_force(cells, seg, dim):
    uses = {}
    for cell, s in zip(cells, seg):
        for i in range(dim + 1):
            f = tuple(sorted(int(v) for j, v in enumerate(cell) if j != i))
            uses.setdefault(f, []).append(int(s))
    return {f: tuple(sorted(set(ss))) for f, ss in uses.items() if len(ss) == 2 and ss[0] != ss[1]}


def gmsh_groups(path, dim):
    """{(dim, name): [faces as node-tag tuples]} and node coordinates, by Gmsh's reader."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(path)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = {int(t): np.array(coords[3 * k:3 * k + 3][:dim]) for k, t in enumerate(tags)}
    groups = {}
    for d, tag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(d, tag)
        faces = []
        for e in gmsh.model.getEntitiesForPhysicalGroup(d, tag):
            types, _, nodes = gmsh.model.mesh.getElements(d, e)
            for t, ns in zip(types, nodes):
                n = gmsh.model.mesh.getElementProperties(t)[3]
                faces += [tuple(int(v) for v in ns[k:k + n]) for k in range(0, len(ns), n)]
        groups[(d, name)] = faces
    gmsh.finalize()
    return groups, xyz


def run_case(mesh, src, work, dim):
    name = "mosfet" if dim == 3 else "mosfet2d"
    poly = os.path.join(work, name + ".poly")
    pts, facets = marked_input(os.path.join(src, "examples", name + ".poly"), poly, dim)
    side = json.load(open(os.path.join(src, "examples", name + ".json")))
    side["facets"] = {"77": "drain_contact", "78": "source_contact"}
    json.dump(side, open(os.path.join(work, name + ".json"), "w"))
    size = "0.1" if dim == 3 else "0.05"
    outs = {"node": name + "_m.node", "msh41": name + "_41.msh", "msh22": name + "_22.msh", "vtu": name + "_m.vtu"}
    for key, out in outs.items():
        cmd = [mesh, poly, "--size", size, "--quiet", "-o", os.path.join(work, out)] + (["--msh", "2.2"] if key == "msh22" else [])
        r = subprocess.run(cmd, capture_output=True, text=True)
        check(r.returncode == 0, f"{dim}D gsse-mesh -o {out} {r.stderr.strip()}")
    # .node/.face (.edge)
    base = os.path.join(work, name + "_m")
    node = [l.split() for l in open(base + ".node") if l.strip() and not l.startswith("#")]
    xyz = np.array([[float(v) for v in r[1:1 + dim]] for r in node[1:]])
    rows = [l.split() for l in open(base + (".face" if dim == 3 else ".edge")) if l.strip() and not l.startswith("#")]
    by_marker = {}
    for r in rows[1:]:
        by_marker.setdefault(int(r[-1]), []).append(xyz[[int(v) - 1 for v in r[1:1 + dim]]])
    covers(pts, facets[0], by_marker.get(77, []), f"{dim}D .{'face' if dim == 3 else 'edge'} marker 77")
    covers(pts, facets[1], by_marker.get(78, []), f"{dim}D .{'face' if dim == 3 else 'edge'} marker 78")
    names = json.load(open(base + ".json")).get("facets", {})
    check(names == {"77": "drain_contact", "78": "source_contact"}, f"{dim}D output sidecar names the markers: {names}")
    # .msh, both versions, through Gmsh's reader and meshio
    check(open(os.path.join(work, outs["msh22"])).read().split("\n")[1] == "2.2 0 8", f"{dim}D .msh 2.2 header '2.2 0 8'")
    for key in ("msh41", "msh22"):
        path = os.path.join(work, outs[key])
        groups, nodes = gmsh_groups(path, dim)
        covers(pts, facets[0], [np.array([nodes[v] for v in f]) for f in groups.get((dim - 1, "drain_contact"), [])],
               f"{dim}D {key} (Gmsh) group drain_contact")
        segs = [n for (d, n) in groups if d == dim]
        check(sorted(segs) == sorted(side["segments"]), f"{dim}D {key} (Gmsh) volume groups {sorted(segs)}")
        cells, seg = [], []
        for k, s in enumerate(segs):
            cells += groups[(dim, s)]
            seg += [k] * len(groups[(dim, s)])
        want = interfaces_by_brute_force(cells, seg, dim)
        got = {}
        for (d, n), faces in groups.items():
            if d == dim - 1 and ":" in n:
                a, b = n.split(":")
                for f in faces:
                    got[tuple(sorted(f))] = tuple(sorted((segs.index(a), segs.index(b))))
        check(got == want, f"{dim}D {key} (Gmsh) interface groups: {len(got)} faces in {len({v for v in got.values()})} "
                           f"groups, {len(want)} interface faces by brute force")
        m = meshio.read(path)
        check(any(n == "drain_contact" and int(v[1]) == dim - 1 for n, v in m.field_data.items()),
              f"{dim}D {key} (meshio) reads it, group drain_contact present")
    # .vtu companion
    b = meshio.read(os.path.join(work, name + "_m.boundary.vtu"))
    marker = np.concatenate(b.cell_data["marker"])
    faces = np.concatenate([blk.data for blk in b.cells])
    covers(pts, facets[0], [b.points[f][:, :dim] for f in faces[marker == 77]], f"{dim}D .boundary.vtu (meshio) marker 77")


def gmsh_surface_case(mesh, work):
    """A Gmsh model: a unit box whose top surface is the physical group "top_contact" (tag 5),
    surface-meshed by Gmsh; meshed by gsse-mesh, the output .msh has that group, covering the top."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    top = [t for d, t in gmsh.model.getEntities(2) if abs(gmsh.model.occ.getCenterOfMass(2, t)[2] - 1) < 1e-9]
    gmsh.model.addPhysicalGroup(2, top, 5)
    gmsh.model.setPhysicalName(2, 5, "top_contact")
    gmsh.model.addPhysicalGroup(3, [1], 1)
    gmsh.model.setPhysicalName(3, 1, "bulk")
    gmsh.option.setNumber("Mesh.SaveAll", 1)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.5)
    gmsh.model.mesh.generate(2)
    src = os.path.join(work, "box.msh")
    gmsh.write(src)
    gmsh.finalize()
    out = os.path.join(work, "box_out.msh")
    r = subprocess.run([mesh, src, "--size", "0.25", "--quiet", "-o", out], capture_output=True, text=True)
    check(r.returncode == 0, f"Gmsh surface model with a named surface group meshed {r.stderr.strip()}")
    groups, nodes = gmsh_groups(out, 3)
    faces = [np.array([nodes[v] for v in f]) for f in groups.get((2, "top_contact"), [])]
    area = sum(face_measure(x) for x in faces)
    check(len(faces) > 1 and abs(area - 1) < 1e-9 and all(abs(q[2] - 1) < 1e-12 for x in faces for q in x),
          f"Gmsh model: output group top_contact, {len(faces)} faces of area {area:.12g} on the top; volumes {sorted(n for d, n in groups if d == 3)}")


def main():
    mesh, src = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory(prefix="gsse_markers_") as work:
        for dim in (3, 2):
            run_case(mesh, src, work, dim)
        gmsh_surface_case(mesh, work)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
