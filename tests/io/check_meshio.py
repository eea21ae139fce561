#!/usr/bin/env python3
"""Independent check of our writers: meshio reads the .vtu and .msh files io_write_samples wrote
and must find the point and cell counts and the segment number of every cell ("segment" cell
data in .vtu, "gmsh:physical" in .msh). Then meshio writes a binary .msh 4.1 of its own, and
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
        got_cells = sum(len(b.data) for b in m.cells)
        key = "segment" if path.endswith(".vtu") else "gmsh:physical"
        seg = np.concatenate(m.cell_data[key]) if key in m.cell_data else np.array([])
        ok = len(m.points) == npts and got_cells == ncells and np.array_equal(seg, expected_cells(runs))
        if path.endswith(".vtu"):
            names = sorted(m.point_data)
            ok = ok and "silicon/potential" in names and "volume" in m.cell_data
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
