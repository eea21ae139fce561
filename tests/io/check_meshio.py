#!/usr/bin/env python3
"""Independent check of our writers: meshio reads the .vtu and .msh files io_write_samples wrote
and must find the point and cell counts and the segment number of every cell ("segment" cell
data in .vtu, "gmsh:physical" in .msh), every cell positively oriented (vertex order kept), and in
the .vtu the quantity values io_write_samples set (a potential that is a function of the
coordinates, each cell's signed volume, recomputed here). In a .msh, the faces of dimension D-1 must be exactly
the interface faces between the two segments (found here by brute force from the cells), in one
physical group named "<first>:<second>"; the .vtu's companion BASE.boundary.vtu must list every
face of the segments' boundaries once. Then meshio writes a binary .msh 4.1 of its own, and
our reader (io_write_samples --read) must read it back with the same counts and segments.

usage: check_meshio.py SAMPLE_DIR IO_WRITE_SAMPLES"""
import os
import subprocess
import sys

try:
    import meshio
    import numpy as np
except ImportError as e:  # reported as a skip by ctest (SKIP_REGULAR_EXPRESSION)
    print(f"SKIPPED: meshio not available ({e})")
    sys.exit(0)


def expected_cells(runs):
    return np.concatenate([np.full(n, num) for num, n in runs])


def main():
    sample_dir, helper = sys.argv[1], sys.argv[2]
    failures = 0
    with open(os.path.join(sample_dir, "manifest.txt")) as f:
        rows = [line.split() for line in f if line.strip()]
    for row in rows:
        path, npts, ncells = row[0], int(row[1]), int(row[2])
        runs = [(int(row[k]), int(row[k + 1])) for k in range(3, len(row), 2)]
        m = meshio.read(path)
        dim = 3 if any(b.type == "tetra" for b in m.cells) else 2
        top = "tetra" if dim == 3 else "triangle"
        key = "segment" if path.endswith(".vtu") else "gmsh:physical"
        blocks = [k for k, b in enumerate(m.cells) if b.type == top]
        got_cells = sum(len(m.cells[k].data) for k in blocks)
        seg = np.concatenate([m.cell_data[key][k] for k in blocks]) if key in m.cell_data else np.array([])
        # faces of the cells: interface (two segments) and boundary (one cell) faces, brute force
        cells = np.concatenate([m.cells[k].data for k in blocks])
        uses = {}
        for c, (cell, s) in enumerate(zip(cells, seg)):
            for i in range(dim + 1):
                f = tuple(sorted(int(v) for j, v in enumerate(cell) if j != i))
                uses.setdefault(f, []).append(int(s))
        interface = {f for f, ss in uses.items() if len(ss) == 2 and ss[0] != ss[1]}
        outer = {f for f, ss in uses.items() if len(ss) == 1}
        if path.endswith(".msh"):
            faces = [k for k, b in enumerate(m.cells) if b.type == ("triangle" if dim == 3 else "line")]
            got = [tuple(sorted(int(v) for v in f)) for k in faces for f in m.cells[k].data]
            tags = {int(t) for k in faces for t in m.cell_data["gmsh:physical"][k]}
            names = {int(v[0]): n for n, v in m.field_data.items() if int(v[1]) == dim - 1}
            e = m.points[cells[:, 1:]][:, :, :dim] - m.points[cells[:, :1]][:, :, :dim]
            positive = np.all(np.linalg.det(e) > 0)  # the cells' vertex order (orientation) kept
            faces_ok = sorted(got) == sorted(interface) and len(tags) == 1 and ":" in names.get(tags.pop(), "") and positive
            print(f"{'ok  ' if faces_ok else 'FAIL'} {os.path.basename(path)}: {len(got)} faces of dimension {dim - 1}, "
                  f"{len(interface)} interface faces by brute force, groups {sorted(names.values())}, cells positive: {positive}")
            failures += not faces_ok
        else:
            b = meshio.read(path.replace(".vtu", ".boundary.vtu"))
            got = [tuple(sorted(int(v) for v in f)) for blk in b.cells for f in blk.data]
            faces_ok = sorted(got) == sorted(interface | outer) and len(got) == len(set(got))
            print(f"{'ok  ' if faces_ok else 'FAIL'} {os.path.basename(path)}: boundary.vtu {len(got)} faces, "
                  f"{len(interface)} interface + {len(outer)} outer by brute force")
            failures += not faces_ok
        ok = len(m.points) == npts and got_cells == ncells and np.array_equal(seg, expected_cells(runs))
        if path.endswith(".vtu"):
            names = sorted(m.point_data)
            ok = ok and "silicon/potential" in names and "volume" in m.cell_data
            # values (write_samples.cpp): silicon's potential x + 2y (+ 3z), oxide's 0.5 but its
            # number (2) at vertex 0, and each cell's signed volume, recomputed here
            x = m.points
            want = x[:, 0] + 2 * x[:, 1] + 3 * x[:, 2] if dim == 3 else x[:, 0] + 2 * x[:, 1]
            ox = np.full(len(x), 0.5)
            ox[0] = 2
            vol = np.concatenate([m.cell_data["volume"][k] for k in blocks])
            e = x[cells[:, 1:]] - x[cells[:, :1]]
            signed = (np.linalg.det(e) / 6 if dim == 3 else (e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0]) / 2)
            values_ok = (np.array_equal(m.point_data["silicon/potential"], want) and np.array_equal(m.point_data["oxide/potential"], ox)
                         and np.allclose(vol, signed, rtol=1e-14, atol=0) and np.all(signed > 0))
            print(f"{'ok  ' if values_ok else 'FAIL'} {os.path.basename(path)}: quantity values, and cell volumes "
                  f"{signed.min():.4g}..{signed.max():.4g} (all positive) as written")
            failures += not values_ok
        print(f"{'ok  ' if ok else 'FAIL'} {os.path.basename(path)}: {len(m.points)} points, {got_cells} cells, "
              f"{key} runs {[(int(v), int((seg == v).sum())) for v in dict.fromkeys(seg.tolist())]}")
        failures += not ok
        if path.endswith(".msh") and "binary" not in path:
            # the other direction: meshio's binary .msh 4.1 through our reader
            out = path.replace(".msh", "_meshio_binary.msh")
            meshio.write(out, m, file_format="gmsh", binary=True)
            r = subprocess.run([helper, "--read", out, str(npts), str(ncells)], capture_output=True, text=True)
            got = [line.split()[1:3] for line in r.stdout.splitlines() if line.startswith("segment")]
            want = [[str(a), str(b)] for a, b in runs]
            ok2 = r.returncode == 0 and got == want
            print(f"{'ok  ' if ok2 else 'FAIL'} {os.path.basename(out)} read by gsse: {r.stdout.strip()} {r.stderr.strip()}")
            failures += not ok2
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
