#!/usr/bin/python3
"""Regenerates the corpus of real surface inputs (tests/corpus/inputs/) and its MANIFEST.tsv.

Every input is made by a Debian package's own tool from a model that package ships; nothing in it
was written by the GSSE project:
  - Gmsh's tutorials and demos (gmsh-doc), surface-meshed by `gmsh -2 -save_all` (.msh 4.1, a few
    as binary 4.1 or 2.2), with their volumes and physical groups;
  - CAD parts of Open CASCADE's sample data (occt-misc, BREP and STEP), surface-meshed by gmsh;
  - OpenSCAD's examples (openscad), exported as STL or OFF by `openscad -o` under xvfb-run.
Missing packages are installed with apt-get. The output is the same on every run: gmsh runs with
one thread; OpenSCAD writes the same triangles in an order that changes from run to run, so its
STL facets are sorted (as text) and its OFF vertices sorted (faces renumbered, each started at its
smallest vertex, then sorted): the same surface, the same orientation. Gmsh's thicksolid demo
(OpenCASCADE offsets) meshes differently from run to run and is left out. Also left out on purpose: Gmsh's t16, t18 and the boolean demos compsolid2 and slicer (kept aside
for another purpose), 2D-only models, open surfaces, and models whose gmsh surface mesh
self-intersects (checked with `tetgen -d` when the list was made).

The inputs are stored gzip-compressed (inputs/NAME.EXT.gz); corpus_mesh.sh unpacks them.

Usage: make_corpus.py [--out DIR] [--only NAME...]   (default DIR: the inputs/ folder beside this file;
       with --only, MANIFEST.tsv is left as it is)
"""
import argparse
import collections
import gzip
import os
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
GMSH_DOC = "/usr/share/doc/gmsh-doc/doc/gmsh"
OCC_DATA = "/usr/share/opencascade/data"
SCAD = "/usr/share/openscad/examples"

LICENCES = {
    "gmsh-doc": "GPL-2+ with Gmsh exception",
    "occt-misc": "LGPL-2.1 with OpenCASCADE exception",
    "openscad": "CC0-1.0",
}

# name, package, source file, tool, output format, extra tool arguments
CASES = [
    # Gmsh tutorials (several volumes, holes, STL remeshing, embedded entities, STEP import)
    ("gmsh_t2", "gmsh-doc", f"{GMSH_DOC}/tutorial/t2.geo.gz", "gmsh", "msh41", []),
    ("gmsh_t5", "gmsh-doc", f"{GMSH_DOC}/tutorial/t5.geo.gz", "gmsh", "msh41", []),
    ("gmsh_t13", "gmsh-doc", f"{GMSH_DOC}/tutorial/t13.geo", "gmsh", "msh41b", []),
    ("gmsh_t14", "gmsh-doc", f"{GMSH_DOC}/tutorial/t14.geo", "gmsh", "msh41", []),
    ("gmsh_t15", "gmsh-doc", f"{GMSH_DOC}/tutorial/t15.geo", "gmsh", "msh41", []),
    ("gmsh_t19", "gmsh-doc", f"{GMSH_DOC}/tutorial/t19.geo", "gmsh", "msh41", ["-clscale", "1.5"]),
    ("gmsh_t20", "gmsh-doc", f"{GMSH_DOC}/tutorial/t20.geo", "gmsh", "msh41", []),
    # Gmsh OpenCASCADE demos: booleans, fillets, chamfers, pipes, sweeps, fragments
    ("gmsh_baffles", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/baffles.geo", "gmsh", "msh41", []),
    ("gmsh_boolean", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/boolean.geo", "gmsh", "msh41b", []),
    ("gmsh_chamfer", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/chamfer.geo", "gmsh", "msh41", []),
    ("gmsh_coherence", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/coherence.geo", "gmsh", "msh41", []),
    ("gmsh_extrude", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/extrude.geo", "gmsh", "msh41", []),
    ("gmsh_fillet", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/fillet.geo", "gmsh", "msh41", []),
    ("gmsh_fillet2", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/fillet2.geo", "gmsh", "msh41", ["-clscale", "2"]),
    ("gmsh_hybrid_occ_builtin", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/hybrid_occ_builtin.geo", "gmsh", "msh41", []),
    ("gmsh_periodic", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/periodic.geo", "gmsh", "msh41", []),
    ("gmsh_pipe", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/pipe.geo", "gmsh", "msh41", []),
    ("gmsh_primitives", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/primitives.geo", "gmsh", "msh41", []),
    ("gmsh_revolve", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/revolve.geo", "gmsh", "msh41", []),
    ("gmsh_simple5", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/simple5.geo", "gmsh", "msh41", []),
    ("gmsh_fillet_chamfer", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/fillet_chamfer.geo", "gmsh", "msh41", []),
    ("gmsh_thrusections", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/thrusections.geo", "gmsh", "msh41", []),
    ("gmsh_twist", "gmsh-doc", f"{GMSH_DOC}/demos/boolean/twist.geo", "gmsh", "msh41", []),
    # Gmsh built-in kernel demos (structured hexahedral quadrangles, many volumes, spheres)
    ("gmsh_cone", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/cone.geo", "gmsh", "msh41", []),
    ("gmsh_filter", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/filter.geo.gz", "gmsh", "msh41", []),
    ("gmsh_hex", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/hex.geo", "gmsh", "msh41", []),
    ("gmsh_indheat", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/indheat.geo.gz", "gmsh", "msh41", []),
    ("gmsh_piece", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/piece.geo", "gmsh", "msh41", []),
    ("gmsh_sphere", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/sphere.geo", "gmsh", "msh22", ["-clscale", "0.5"]),
    ("gmsh_cube", "gmsh-doc", f"{GMSH_DOC}/demos/simple_geo/cube.geo", "gmsh", "msh22b", []),
    # Open CASCADE sample CAD parts, meshed by gmsh
    ("occ_chair", "occt-misc", f"{OCC_DATA}/occ/MODERN_Chair_1.brep", "gmsh", "msh41", []),
    ("occ_mvcooker", "occt-misc", f"{OCC_DATA}/occ/MODERN_MVCooker_1.brep", "gmsh", "msh41", []),
    ("occ_pump_nut", "occt-misc", f"{OCC_DATA}/occ/Pump_Nut.brep", "gmsh", "msh41", []),
    ("occ_mal_ecrou", "occt-misc", f"{OCC_DATA}/occ/mal_ecrou.brep", "gmsh", "msh41", []),
    ("occ_hammer", "occt-misc", f"{OCC_DATA}/occ/hammer.brep", "gmsh", "msh41", []),
    ("occ_fuse", "occt-misc", f"{OCC_DATA}/occ/fuse.brep", "gmsh", "msh41", []),
    ("occ_linkrods", "occt-misc", f"{OCC_DATA}/step/linkrods.step", "gmsh", "msh41", []),
    ("occ_screw", "occt-misc", f"{OCC_DATA}/step/screw.step", "gmsh", "msh41", ["-clscale", "0.5"]),
    # OpenSCAD examples: CSG parts with small features, exported as STL (ASCII) or OFF
    ("scad_example001", "openscad", f"{SCAD}/Old/example001.scad", "openscad", "stl", []),
    ("scad_example002", "openscad", f"{SCAD}/Old/example002.scad", "openscad", "off", []),
    ("scad_example004", "openscad", f"{SCAD}/Old/example004.scad", "openscad", "stl", []),
    ("scad_example007", "openscad", f"{SCAD}/Old/example007.scad", "openscad", "off", []),
    ("scad_example009", "openscad", f"{SCAD}/Old/example009.scad", "openscad", "stl", []),
    ("scad_example016", "openscad", f"{SCAD}/Old/example016.scad", "openscad", "stl", []),
    ("scad_example021", "openscad", f"{SCAD}/Old/example021.scad", "openscad", "stl", []),
    ("scad_example023", "openscad", f"{SCAD}/Old/example023.scad", "openscad", "off", []),
    ("scad_csg", "openscad", f"{SCAD}/Basics/CSG.scad", "openscad", "stl", []),
    ("scad_linear_extrude", "openscad", f"{SCAD}/Basics/linear_extrude.scad", "openscad", "stl", []),
    ("scad_sign", "openscad", f"{SCAD}/Parametric/sign.scad", "openscad", "stl", []),
]

EXTENSION = {"msh41": ".msh", "msh41b": ".msh", "msh22": ".msh", "msh22b": ".msh", "stl": ".stl", "off": ".off"}
TOOLS = {"gmsh": ["gmsh", "python3-gmsh"], "openscad": ["openscad", "xvfb"]}


def ensure_packages(pkgs):
    missing = [p for p in pkgs if subprocess.run(["dpkg", "-s", p], capture_output=True).returncode != 0]
    if missing:
        print("installing " + " ".join(missing), flush=True)
        sudo = [] if os.geteuid() == 0 else ["sudo"]
        subprocess.run(sudo + ["apt-get", "update", "-q"], check=True)
        subprocess.run(sudo + ["apt-get", "install", "-y", "-q", "--no-install-recommends"] + missing, check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))


def version(pkg):
    return subprocess.run(["dpkg-query", "-W", "-f=${Version}", pkg], capture_output=True, text=True,
                          check=True).stdout.strip()


def staged_copy(src, tmp):
    """Copies the source's folder (models include and merge their neighbours) and unzips .gz."""
    folder = os.path.join(tmp, "src")
    shutil.copytree(os.path.dirname(src), folder)
    for root, _, files in os.walk(folder):
        for f in files:
            if f.endswith(".gz"):
                with gzip.open(os.path.join(root, f), "rb") as i, open(os.path.join(root, f[:-3]), "wb") as o:
                    shutil.copyfileobj(i, o)
    name = os.path.basename(src)
    return folder, name[:-3] if name.endswith(".gz") else name


def run_gmsh(src, out, fmt, extra, tmp):
    folder, model = staged_copy(src, tmp)
    args = ["gmsh", "-2", "-save_all", "-nt", "1", "-format", fmt[:5]] + (["-bin"] if fmt.endswith("b") else [])
    subprocess.run(args + extra + [model, "-o", out], cwd=folder, check=True, capture_output=True, timeout=600)


def run_openscad(src, out, tmp):
    subprocess.run(["xvfb-run", "-a", "openscad", "-o", out, src], cwd=tmp, check=True, capture_output=True,
                   timeout=600)
    with open(out) as f:
        text = f.read()
    with open(out, "w") as f:
        f.write(canonical_stl(text) if out.endswith(".stl") else canonical_off(text))


def canonical_stl(text):
    """The facets of an ASCII STL sorted as text (OpenSCAD's order varies between runs)."""
    lines = text.splitlines()
    facets, cur = [], []
    for line in lines[1:-1]:
        cur.append(line)
        if line.strip() == "endfacet":
            facets.append("\n".join(cur))
            cur = []
    if cur or not lines[0].startswith("solid") or not lines[-1].startswith("endsolid"):
        raise ValueError("unexpected STL layout")
    return "\n".join([lines[0]] + sorted(facets) + [lines[-1]]) + "\n"


def canonical_off(text):
    """An OFF with its vertices sorted (as text) and its faces renumbered, each rotated to start at
    its smallest vertex (orientation kept), then sorted."""
    lines = [l for l in text.splitlines() if l.strip()]
    nv, nf = (int(x) for x in lines[0].split()[1:3])
    verts = [l.strip() for l in lines[1:1 + nv]]
    order = sorted(range(nv), key=lambda i: verts[i])
    new = {old: k for k, old in enumerate(order)}
    faces = []
    for l in lines[1 + nv:1 + nv + nf]:
        w = l.split()
        f = [new[int(x)] for x in w[1:1 + int(w[0])]]
        k = f.index(min(f))
        faces.append(f[k:] + f[:k])
    faces.sort()
    return "\n".join([lines[0]] + [verts[i] for i in order] +
                     [" ".join(str(x) for x in [len(f)] + f) for f in faces]) + "\n"


def shells(faces):
    """Connected components of faces sharing an edge."""
    up = list(range(len(faces)))

    def find(x):
        while up[x] != x:
            up[x] = up[up[x]]
            x = up[x]
        return x

    first = {}
    for i, f in enumerate(faces):
        for k in range(len(f)):
            e = tuple(sorted((f[k], f[(k + 1) % len(f)])))
            j = first.setdefault(e, i)
            up[find(i)] = find(j)
    return len({find(i) for i in range(len(faces))})


def count_msh(path):
    """(vertices, facets, volumes) of a Gmsh surface mesh, through gmsh's own reader."""
    import gmsh
    gmsh.initialize(["", "-nt", "1"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(path)
    faces = []
    types, _, conn = gmsh.model.mesh.getElements(2)
    for t, c in zip(types, conn):
        per = gmsh.model.mesh.getElementProperties(t)[3]
        faces += [[int(x) for x in c[k:k + per]] for k in range(0, len(c), per)]
    vols = len(gmsh.model.getEntities(3))
    gmsh.finalize()
    return len({v for f in faces for v in f}), len(faces), vols or shells(faces)


def count_stl(path):
    ids, faces, tri = {}, [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "vertex":
                tri.append(ids.setdefault(tuple(w[1:4]), len(ids)))
                if len(tri) == 3:
                    faces.append(tri)
                    tri = []
    return len(ids), len(faces), shells(faces)


def count_off(path):
    with open(path) as f:
        words = f.read().split()
    nv, nf = int(words[1]), int(words[2])
    at, faces = 4 + 3 * nv, []
    for _ in range(nf):
        n = int(words[at])
        faces.append([int(x) for x in words[at + 1:at + 1 + n]])
        at += 1 + n
    return nv, nf, shells(faces)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(HERE, "inputs"))
    ap.add_argument("--only", nargs="*")
    a = ap.parse_args()
    cases = [c for c in CASES if not a.only or c[0] in a.only]
    ensure_packages(sorted({c[1] for c in cases} | {p for c in cases for p in TOOLS[c[3]]}))
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for name, pkg, src, tool, fmt, extra in cases:
        file = name + EXTENSION[fmt]
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, file)
            if tool == "gmsh":
                run_gmsh(src, out, fmt, extra, tmp)
                how = "gmsh -2 -save_all -nt 1 -format " + fmt[:5] + (" -bin" if fmt.endswith("b") else "")
                how += "".join(" " + x for x in extra)
            else:
                run_openscad(src, out, tmp)
                how = "xvfb-run -a openscad -o " + file
            counts = count_msh(out) if fmt.startswith("msh") else count_stl(out) if fmt == "stl" else count_off(out)
            # stored compressed (a third of the size); no name or date in the gzip header
            with open(out, "rb") as i, open(os.path.join(a.out, file + ".gz"), "wb") as raw:
                with gzip.GzipFile(filename="", mode="wb", fileobj=raw, compresslevel=9, mtime=0) as o:
                    shutil.copyfileobj(i, o)
        rows.append([name, file, src, pkg + " " + version(pkg), LICENCES[pkg]] +
                    [str(x) for x in counts] + [how])
        print("%-26s %6s vertices %6s facets %3s volumes" % (name, *counts), flush=True)
    if a.only:
        return
    tools = ", ".join(t + " " + version(t) for t in ("gmsh", "openscad"))
    with open(os.path.join(HERE, "MANIFEST.tsv"), "w") as m:
        m.write("# Real surface inputs made by tests/corpus/make_corpus.py with " + tools + ".\n")
        m.write("# volumes: volume entities (.msh 4.1), else closed shells (.msh 2.2, STL, OFF).\n")
        m.write("\t".join(["name", "file", "source", "package", "licence", "vertices", "facets", "volumes", "how"]) + "\n")
        for r in rows:
            m.write("\t".join(r) + "\n")


if __name__ == "__main__":
    sys.exit(main())
