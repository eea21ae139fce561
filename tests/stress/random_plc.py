#!/usr/bin/env python3
"""Random PLCs for the stress test (tests/stress/stress.sh), one per seed, deterministic.

usage: random_plc.py SEED OUT_BASENAME   -> writes OUT_BASENAME.poly, _bad.poly or .off, prints the path

Kinds, by seed % 5:
  0  box union: a random voxel arrangement (uneven grid lines, 2-4 materials, some voxels empty)
     turned by a random rotation: every facet slanted, right angles everywhere (cocircular ties
     up to rounding), quadrilateral facets coplanar up to rounding, voxels meeting at edges and
     corners only
  1  the same, each quadrilateral written as two triangles (an STL-like split, random diagonal)
  2  a triangulated closed surface (a box whose faces are grids of triangles) with its vertices
     moved along the faces by 1e-13..1e-9 of the box: nearly coplanar neighbours, near-degenerate
     cocircular ties; written as OFF
  3  a box union not rotated, with one pair of grid lines 1e-8..1e-5 apart (a thin layer)
  4  bad input: two rotated boxes that overlap, or a box with a facet piercing it; it must be
     rejected with an error naming the facets
"""
import math
import random
import sys


def rotation(rng):
    # a random rotation (unit quaternion), generic: no facet stays parallel to an axis
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        if n > 1e-3:
            break
    w, x, y, z = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def turn(R, p):
    return tuple(sum(R[i][k] * p[k] for k in range(3)) for i in range(3))


def grid_lines(rng, n, thin=False):
    xs = sorted(rng.uniform(0.1, 0.9) for _ in range(n - 1))
    lines = [0.0] + xs + [1.0]
    if thin:  # one gap made tiny
        k = rng.randrange(1, len(lines) - 1)
        lines.insert(k + 1, lines[k] + 10 ** rng.uniform(-8, -5))
    return lines


def voxels(rng, thin=False):
    X, Y, Z = (grid_lines(rng, rng.randint(2, 3), thin and a == 2) for a in range(3))
    nx, ny, nz = len(X) - 1, len(Y) - 1, len(Z) - 1
    mats = rng.randint(2, 4)
    cell = {}
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                if rng.random() < 0.8 or (i, j, k) == (0, 0, 0):
                    cell[(i, j, k)] = rng.randint(1, mats)
    return X, Y, Z, cell


def box_union(rng, R, triangles, thin=False):
    X, Y, Z, cell = voxels(rng, thin)
    pts, index = [], {}

    def pid(i, j, k):
        key = (i, j, k)
        if key not in index:
            index[key] = len(pts)
            pts.append(turn(R, (X[i], Y[j], Z[k])))
        return index[key]

    facets = []  # (corner ids, marker)
    for (i, j, k), m in sorted(cell.items()):
        for axis in range(3):
            for side in (0, 1):
                n = [i, j, k]
                n[axis] += 1 if side else -1
                other = cell.get(tuple(n), 0)
                if other == m or (other and side == 0):
                    continue  # same material: no facet; a shared face is written once (from below)
                base = [i, j, k]
                base[axis] += side
                u, v = [a for a in range(3) if a != axis]
                quad = []
                for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    c = list(base)
                    c[u] += du
                    c[v] += dv
                    quad.append(pid(*c))
                marker = 100 * min(m, other) + max(m, other) if other else m
                if triangles:
                    if rng.random() < 0.5:
                        facets += [([quad[0], quad[1], quad[2]], marker), ([quad[0], quad[2], quad[3]], marker)]
                    else:
                        facets += [([quad[0], quad[1], quad[3]], marker), ([quad[1], quad[2], quad[3]], marker)]
                else:
                    facets.append((quad, marker))
    regions = []
    for (i, j, k), m in sorted(cell.items()):
        c = ((X[i] + X[i + 1]) / 2, (Y[j] + Y[j + 1]) / 2, (Z[k] + Z[k + 1]) / 2)
        regions.append((turn(R, c), m))
    return pts, facets, regions


def surface(rng):
    # a box whose six faces are n x n grids of triangles, vertices moved along their face
    n = rng.randint(3, 6)
    size = [rng.uniform(0.5, 2) for _ in range(3)]
    pts, index, tris = [], {}, []
    eps = 10 ** rng.uniform(-13, -9)

    def pid(c):
        if c not in index:
            index[c] = len(pts)
            p = [c[a] / n * size[a] for a in range(3)]
            for a in range(3):  # tangential moves only: coordinates on the box's faces stay exact
                if 0 < c[a] < n:
                    p[a] += rng.uniform(-eps, eps)
            pts.append(p)
        return index[c]

    for axis in range(3):
        u, v = [a for a in range(3) if a != axis]
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    cs = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        c = [0, 0, 0]
                        c[axis], c[u], c[v] = side, i + du, j + dv
                        cs.append(pid(tuple(c)))
                    if side == 0:
                        cs.reverse()
                    if (i + j) % 2:
                        tris += [(cs[0], cs[1], cs[2]), (cs[0], cs[2], cs[3])]
                    else:
                        tris += [(cs[0], cs[1], cs[3]), (cs[1], cs[2], cs[3])]
    R = rotation(rng) if rng.random() < 0.5 else None
    if R:
        pts = [turn(R, p) for p in pts]
    return pts, tris


def bad_input(rng):
    R = rotation(rng)
    pts, facets = [], []

    def box(lo, hi, marker):
        base = len(pts)
        for k in range(8):
            pts.append(turn(R, tuple(hi[a] if (k >> a) & 1 else lo[a] for a in range(3))))
        for q in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
            facets.append(([base + i for i in q], marker))

    lo = [0, 0, 0]
    hi = [rng.uniform(0.5, 1) for _ in range(3)]
    box(lo, hi, 1)
    regions = [(turn(R, tuple(h / 2 for h in hi)), 1)]
    if rng.random() < 0.5:  # a second box overlapping the first
        lo2 = [h * rng.uniform(0.3, 0.7) for h in hi]
        hi2 = [a + rng.uniform(0.5, 1) for a in lo2]
        box(lo2, hi2, 2)
        regions.append((turn(R, tuple(h - 1e-3 for h in hi2)), 2))
    else:  # a facet through the top of the box
        x = hi[0] * rng.uniform(0.2, 0.8)
        base = len(pts)
        for y, z in ((0.25, 0.5), (0.75, 0.5), (0.75, 1.5), (0.25, 1.5)):
            pts.append(turn(R, (x, y * hi[1], z * hi[2])))
        facets.append(([base, base + 1, base + 2, base + 3], 3))
    return pts, facets, regions


def write_poly(path, pts, facets, regions):
    with open(path, "w") as f:
        f.write("# random PLC (tests/stress/random_plc.py)\n%d 3 0 0\n" % len(pts))
        for i, p in enumerate(pts):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, *p))
        f.write("%d 1\n" % len(facets))
        for ids, m in facets:
            f.write("1 0 %d\n%d %s\n" % (m, len(ids), " ".join(str(i + 1) for i in ids)))
        f.write("0\n%d\n" % len(regions))
        for k, (c, m) in enumerate(regions):
            f.write("%d %.17g %.17g %.17g %d -1\n" % (k + 1, *c, m))


def main():
    seed, out = int(sys.argv[1]), sys.argv[2]
    rng = random.Random(seed)
    kind = seed % 5
    if kind == 4:
        pts, facets, regions = bad_input(rng)
        path = out + "_bad.poly"  # the stress test requires it to be rejected
        write_poly(path, pts, facets, regions)
    elif kind == 2:
        pts, tris = surface(rng)
        path = out + ".off"
        with open(path, "w") as f:
            f.write("OFF\n%d %d 0\n" % (len(pts), len(tris)))
            for p in pts:
                f.write("%.17g %.17g %.17g\n" % tuple(p))
            for t in tris:
                f.write("3 %d %d %d\n" % t)
    else:
        R = rotation(rng) if kind in (0, 1) else [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
        pts, facets, regions = box_union(rng, R, kind == 1, thin=kind == 3)
        path = out + ".poly"
        write_poly(path, pts, facets, regions)
    print(path)


main()
