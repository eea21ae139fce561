#!/usr/bin/python3
"""Pictures for the README and docs/ from the project's own output (issue 17): the bundled 2D MOSFET
coloured by segment with boundary conforming only, graded (--grade 1.3) and graded with --quality 28,
and a cut through the bundled 3D MOSFET meshed with --size 0.05 (uniform) and with --grade 1.3.

usage: /usr/bin/python3 scripts/pictures.py [GSSE_MESH] [OUT_DIR]
       (defaults: build/apps/gsse-mesh, docs/images; needs python3-matplotlib, which
       scripts/pictures.sh installs)
"""
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESH = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "apps", "gsse-mesh")
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "docs", "images")
COLOURS = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7", "#9c755f"]


def rows(path):
    with open(path) as f:
        return [l.split() for l in f if l.strip() and not l.lstrip().startswith("#")]


def mesh(poly, args, work, name):
    """Runs gsse-mesh (verified) and reads its .node/.ele: points, cells, segment numbers."""
    base = os.path.join(work, name)
    subprocess.run([MESH, poly, "-o", base + ".node", "--verify", "--quiet", "--threads", "2"] + args, check=True)
    node = rows(base + ".node")
    n, dim = int(node[0][0]), int(node[0][1])
    pts = [tuple(float(x) for x in r[1:1 + dim]) for r in node[1:1 + n]]
    ele = rows(base + ".ele")
    m, k = int(ele[0][0]), int(ele[0][1])
    cells = [[int(x) - 1 for x in r[1:1 + k]] for r in ele[1:1 + m]]
    seg = [int(r[1 + k]) for r in ele[1:1 + m]]
    return pts, cells, seg


def draw(ax, polys, seg, title, count):
    ax.add_collection(PolyCollection(polys, facecolors=[COLOURS[(s - 1) % len(COLOURS)] for s in seg],
                                     edgecolors="black", linewidths=0.15))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_title(f"{title}\n{count}", fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def cut(pts, cells, seg, axis, at):
    """The polygons where the plane x[axis] = at cuts the tetrahedra (exactly on the plane: skipped)."""
    out, col = [], []
    keep = [a for a in range(3) if a != axis]
    for c, s in zip(cells, seg):
        d = [pts[v][axis] - at for v in c]
        if min(d) >= 0 or max(d) <= 0:
            continue
        q = []
        for i in range(4):
            for j in range(i + 1, 4):
                if (d[i] < 0) != (d[j] < 0):
                    t = d[i] / (d[i] - d[j])
                    a, b = pts[c[i]], pts[c[j]]
                    q.append(tuple(a[x] + t * (b[x] - a[x]) for x in keep))
        cx, cy = sum(p[0] for p in q) / len(q), sum(p[1] for p in q) / len(q)
        import math
        q.sort(key=lambda p: math.atan2(p[1] - cy, p[0] - cx))
        out.append(q)
        col.append(s)
    return out, col


def main():
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        poly2 = os.path.join(ROOT, "examples", "mosfet2d.poly")
        fig, axes = plt.subplots(1, 3, figsize=(13, 3.6))
        for ax, (args, title) in zip(axes, [([], "boundary conforming only"), (["--grade", "1.3"], "--grade 1.3"),
                                            (["--grade", "1.3", "--quality", "28"], "--grade 1.3 --quality 28")]):
            pts, cells, seg = mesh(poly2, args, work, "m2")
            draw(ax, [[pts[v] for v in c] for c in cells], seg, "gsse-mesh mosfet2d.poly " + title, f"{len(cells):,} triangles")
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, "mosfet2d_sizing.png"), dpi=130, bbox_inches="tight")
        plt.close(fig)

        poly3 = os.path.join(ROOT, "examples", "mosfet.poly")
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
        for ax, (args, title) in zip(axes, [(["--size", "0.05"], "--size 0.05 (uniform)"), (["--grade", "1.3"], "--grade 1.3")]):
            pts, cells, seg = mesh(poly3, args, work, "m3")
            ys = sorted(p[1] for p in pts)
            at = 0.5 * (ys[0] + ys[-1]) + 1e-7 * (ys[-1] - ys[0])  # off any lattice plane
            polys, col = cut(pts, cells, seg, 1, at)
            draw(ax, polys, col, f"gsse-mesh mosfet.poly {title}: cut y = {at:.3f}", f"{len(cells):,} tetrahedra")
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, "mosfet3d_cut.png"), dpi=130, bbox_inches="tight")
        plt.close(fig)
    print("wrote", os.path.join(OUT, "mosfet2d_sizing.png"), "and", os.path.join(OUT, "mosfet3d_cut.png"))


if __name__ == "__main__":
    main()
