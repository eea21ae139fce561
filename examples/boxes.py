#!/usr/bin/env python3
"""Writes the bundled example structures: unions of axis-aligned boxes, one material per box
(later boxes win), as TetGen .poly (3D) or Triangle .poly (2D, the x-z section), plus a .json
sidecar with the segment names (segment k is names[k-1]).

Faces are cut on the grid of all box coordinates, so interfaces meet edge to edge.

Usage: boxes.py NAME [--dim 2|3] [--out DIR]      NAME: mosfet | stack
"""
import argparse, itertools, json, os

EXAMPLES = {
    # planar MOSFET, lengths in micrometres
    "mosfet": [("substrate", (0, 0, -0.5), (1, 0.5, 0)),
               ("gate_oxide", (0.4, 0, 0), (0.6, 0.5, 0.02)),
               ("gate", (0.4, 0, 0.02), (0.6, 0.5, 0.2)),
               ("spacer_source", (0.3, 0, 0), (0.4, 0.5, 0.2)),
               ("spacer_drain", (0.6, 0, 0), (0.7, 0.5, 0.2)),
               ("contact_source", (0, 0, 0), (0.2, 0.5, 0.05)),
               ("contact_drain", (0.8, 0, 0), (1, 0.5, 0.05))],
    # two stacked layers
    "stack": [("silicon", (0, 0, -1), (1, 1, 0)), ("oxide", (0, 0, 0), (1, 1, 0.25))],
}


def build(boxes, dim):
    axes = range(dim)
    grid = [sorted({b[1][a] for b in boxes} | {b[2][a] for b in boxes}) for a in axes]
    names = list(dict.fromkeys(b[0] for b in boxes))
    owner = {}
    for cell in itertools.product(*[range(len(g) - 1) for g in grid]):
        mid = [(grid[a][cell[a]] + grid[a][cell[a] + 1]) / 2 for a in axes]
        for name, lo, hi in boxes:
            if all(lo[a] <= mid[a] <= hi[a] for a in axes):
                owner[cell] = names.index(name) + 1
    ids = {}

    def vid(corner):
        return ids.setdefault(corner, len(ids) + 1)

    faces = []
    for cell, seg in sorted(owner.items()):
        for a in axes:
            up = list(cell); up[a] += 1
            other = owner.get(tuple(up), 0)
            down = list(cell); down[a] -= 1
            for side, nb in ((cell[a] + 1, other), (cell[a], owner.get(tuple(down), 0))):
                if nb == seg or (nb and nb < seg):
                    continue  # inside a segment, or written from the lower-numbered side
                rest = [b for b in axes if b != a]
                corners = []
                for offs in ([(0,), (1,)] if dim == 2 else [(0, 0), (1, 0), (1, 1), (0, 1)]):
                    c = list(cell); c[a] = side
                    for b, o in zip(rest, offs):
                        c[b] = cell[b] + o
                    corners.append(vid(tuple(c)))
                faces.append((corners, seg * 100 + nb))
    coords = {i: [grid[a][c[a]] for a in axes] for c, i in ids.items()}
    regions = []
    for seg in range(1, len(names) + 1):
        for cell, s in sorted(owner.items()):
            if s == seg:
                regions.append(([(grid[a][cell[a]] + grid[a][cell[a] + 1]) / 2 for a in axes], seg))
                break
    return names, coords, faces, regions


def write(path, dim, coords, faces, regions):
    with open(path, "w") as f:
        f.write(f"{len(coords)} {dim} 0 0\n")
        for i in sorted(coords):
            f.write(f"{i} " + " ".join(repr(float(x)) for x in coords[i]) + "\n")
        f.write(f"{len(faces)} 1\n")
        for k, (c, m) in enumerate(faces, 1):
            f.write(f"1 0 {m}\n4 {' '.join(map(str, c))}\n" if dim == 3 else f"{k} {c[0]} {c[1]} {m}\n")
        f.write("0\n" + f"{len(regions)}\n")
        for k, (p, s) in enumerate(regions, 1):
            f.write(f"{k} " + " ".join(repr(x) for x in p) + f" {s} -1\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("name", choices=sorted(EXAMPLES))
    ap.add_argument("--dim", type=int, default=3, choices=(2, 3))
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    a = ap.parse_args()
    boxes = EXAMPLES[a.name]
    if a.dim == 2:
        boxes = [(n, (lo[0], lo[2]), (hi[0], hi[2])) for n, lo, hi in boxes]
    names, coords, faces, regions = build(boxes, a.dim)
    stem = a.name if a.dim == 3 else a.name + "2d"
    write(os.path.join(a.out, stem + ".poly"), a.dim, coords, faces, regions)
    with open(os.path.join(a.out, stem + ".json"), "w") as f:
        json.dump({"segments": names}, f)


if __name__ == "__main__":
    main()
