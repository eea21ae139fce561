#!/usr/bin/env bash
# Documented CLI behaviours, each checked against an independent reading of the output:
#  --stats      its counts equal those of the written .node/.ele (read here);
#  --max-steiner  a cap the job needs more than ends with exit 1, a message naming the cap, no file;
#  --rules      split rules replace the conformer's: with a set whose every rule is `midpoint`, the
#               conformer's trace shows midpoint splits only, where the defaults project and rotate;
#  hole points  a volume hole point empties its cell: the tetrahedra's volume is the cube's minus
#               the inner box's (computed here from .node/.ele);
#  --verify     PASS on a good mesh, exit 0; on a cube turned by a generic rotation with
#               --verify-tol 0 (faces on slanted facets only within rounding: the verifier must
#               reject them), FAIL: exit 3, the problems on stderr, and neither -o nor --stats
#               written; the same run at the default tolerance passes and writes both;
#  --check      an existing mesh against the input: the good mesh passes (exit 0); the same mesh
#               with one tetrahedron dropped, or with the inner box relabelled as the outer
#               region, fails with exit 3 and the verifier's problem on stderr (the verdict and
#               exit status are the code --verify's failure goes through);
#  --quality    on a needle (a pyramid with a 14-degree apex in a box): --stats lists the elements
#               excepted at the apex under excepted_near (the apex's coordinates, as many as
#               `excepted`), the summary names the point; --quality-rounds 3 stops after 3 rounds
#               (not converged); --acute-guard 0 excepts nothing.
#  --size-fit   quality.size_fit in --stats equals the counts read back from the mesh written
#  size rounds  3D --size without --quality: the summary's "size rounds" line, --stats'
#               quality.refinement with "for": "size" and "bound": null; --no-size-rounds: neither
#  overwrites   a run that would write over its own input, the input's sidecar (-o BASE.node
#               beside BASE.poly writes BASE.json; --stats BASE.json) or the --cloud file, or
#               write one file twice (--stats g.json with -o g.node), exits 1 before meshing with
#               a message naming both, and the sidecar is byte-identical afterwards; a --stats
#               file put where a sidecar is read is named as such.
#  allocator    the run sets glibc's malloc tunables for itself (--stats' "malloc" equals the
#               string in apps/allocator_tuning.hpp), GSSE_MALLOC=system leaves them out (null),
#               a GLIBC_TUNABLES of the user's own is kept as given (a sanitizer build sets
#               nothing: its allocator is the sanitizer's); the mesh is byte-identical
#               either way (nothing may depend on where memory lies), with 1 and 2 threads.
# usage: cli_behaviour.sh GSSE_MESH SOURCE_DIR
set -uo pipefail
mesh=$1; src=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }
py=/usr/bin/python3; [ -x $py ] || py=python3
# a unit cube with a box [0.3, 0.7]^3 inside, region 1 outside it and (optionally) a hole inside
box_poly() {  # file, "hole" or "region"
  $py - "$1" "$2" <<'PY'
import sys
path, inner = sys.argv[1], sys.argv[2]
def box(lo, hi, first):
    P = [(x, y, z) for z in (lo, hi) for y in (lo, hi) for x in (lo, hi)]
    F = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return P, [tuple(first + i + 1 for i in f) for f in F]
P1, F1 = box(0.0, 1.0, 0)
P2, F2 = box(0.3, 0.7, 8)
with open(path, "w") as f:
    f.write(f"16 3 0 0\n" + "".join(f"{i+1} {p[0]} {p[1]} {p[2]}\n" for i, p in enumerate(P1 + P2)))
    f.write("12 0\n" + "".join("1\n4 %d %d %d %d\n" % q for q in F1 + F2))
    if inner == "hole":
        f.write("1\n1 0.5 0.5 0.5\n1\n1 0.1 0.1 0.1 1 -1\n")
    else:
        f.write("0\n2\n1 0.1 0.1 0.1 1 -1\n2 0.5 0.5 0.5 2 -1\n")
PY
}
volume() {  # base: total volume of the tetrahedra of BASE.node/.ele
  $py - "$1" <<'PY'
import sys
b = sys.argv[1]
rows = lambda f: [l.split() for l in open(f) if l.strip() and not l.startswith("#")][1:]
P = {int(r[0]): tuple(map(float, r[1:4])) for r in rows(b + ".node")}
v = 0.0
for r in rows(b + ".ele"):
    a, b_, c, d = (P[int(x)] for x in r[1:5])
    u = [b_[k] - a[k] for k in range(3)]; w = [c[k] - a[k] for k in range(3)]; z = [d[k] - a[k] for k in range(3)]
    v += abs(u[0] * (w[1] * z[2] - w[2] * z[1]) - u[1] * (w[0] * z[2] - w[2] * z[0]) + u[2] * (w[0] * z[1] - w[1] * z[0])) / 6
print(f"{v:.12f}")
PY
}
count() { awk '!/^#/ && NF { print $1; exit }' "$1"; }

# --stats against the files
box_poly "$work/box.poly" region
"$mesh" "$work/box.poly" --size 0.2 --quiet -o "$work/m.node" --stats "$work/s.json" || bad "box did not mesh"
read -r sp sc < <($py -c "import json; d=json.load(open('$work/s.json')); print(d['points'], sum(s['cells'] for s in d['segments']))")
if [ "$sp" = "$(count "$work/m.node")" ] && [ "$sc" = "$(count "$work/m.ele")" ] && [ "$sp" -gt 16 ]; then
  ok "--stats: $sp points and $sc cells, as in m.node and m.ele"
else bad "--stats says $sp points, $sc cells; files have $(count "$work/m.node"), $(count "$work/m.ele")"; fi

# --max-steiner
rm -f "$work/cap.node"
msg=$("$mesh" "$work/box.poly" --size 0.05 --max-steiner 10 --quiet -o "$work/cap.node" 2>&1); rc=$?
if [ $rc = 1 ] && [[ "$msg" == *"more than 10 "* ]] && [ ! -e "$work/cap.node" ]; then ok "--max-steiner 10: exit 1, '$msg'"
else bad "--max-steiner 10: exit $rc, '$msg'"; fi

# --rules: every split rule midpoint
sed -E 's/^  try (shell|project|rotate-vertex|rotate-edge).*$//' "$src/rules/conformer3d.rules" > "$work/midpoint.rules"
trace_actions() { GSSE_CONFORM_TRACE=1 "$mesh" "$work/box.poly" --quiet "$@" 2>&1 | awk '/^   / { split($1, a, "/"); print a[3] }' | sort -u | tr '\n' ' '; }
default=$(trace_actions)
custom=$(trace_actions --rules "$work/midpoint.rules")
if [ "$custom" = "midpoint " ] && [ "$default" != "midpoint " ] && [ -n "$default" ]; then
  ok "--rules: actions fired with the defaults: $default; with an all-midpoint set: $custom"
else bad "--rules: defaults fired '$default', the all-midpoint set '$custom'"; fi

# volume hole point
box_poly "$work/hole.poly" hole
"$mesh" "$work/hole.poly" --quiet -o "$work/h.node" || bad "holed box did not mesh"
v=$(volume "$work/h"); want=$(echo "1 - 0.4^3" | bc -l)
if $py -c "import sys; sys.exit(0 if abs($v - $want) < 1e-12 else 1)"; then ok "hole point: tetrahedra volume $v = 1 - 0.4^3"
else bad "hole point: volume $v, expected $want"; fi
v2=$(volume "$work/m")
if $py -c "import sys; sys.exit(0 if abs($v2 - 1) < 1e-12 else 1)"; then ok "without the hole: volume $v2"; else bad "volume $v2"; fi

# --verify PASS
out=$("$mesh" "$work/box.poly" --size 0.2 --verify -o "$work/v.vtu" 2>&1); rc=$?
if [ $rc = 0 ] && [[ "$out" == *"verify: PASS"* ]] && [ -e "$work/v.vtu" ]; then ok "--verify: PASS, exit 0, output written"
else bad "--verify: exit $rc"; fi
# --verify failing: a rotated cube, verified with tolerance 0
$py - "$work/rot.poly" <<'PY'
import sys, math
a, b, c = 0.3, 0.7, 1.1  # a generic rotation: no facet parallel to an axis
def rot(p):
    x, y, z = p
    x, y = x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a)
    y, z = y * math.cos(b) - z * math.sin(b), y * math.sin(b) + z * math.cos(b)
    z, x = z * math.cos(c) - x * math.sin(c), z * math.sin(c) + x * math.cos(c)
    return x, y, z
P = [rot((x, y, z)) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
F = [(1, 2, 4), (1, 4, 3), (5, 6, 8), (5, 8, 7), (1, 2, 6), (1, 6, 5), (3, 4, 8), (3, 8, 7), (1, 3, 7), (1, 7, 5), (2, 4, 8), (2, 8, 6)]
with open(sys.argv[1], "w") as f:
    f.write("8 3 0 0\n" + "".join(f"{i+1} {p[0]!r} {p[1]!r} {p[2]!r}\n" for i, p in enumerate(P)))
    f.write("12 0\n" + "".join("1\n3 %d %d %d\n" % t for t in F) + "0\n1\n1 %r %r %r 1 -1\n" % rot((0.5, 0.5, 0.5)))
PY
out=$("$mesh" "$work/rot.poly" --size 0.2 --verify-tol 0 -o "$work/rot.vtu" --stats "$work/rot.stats.json" 2>"$work/rot.err"); rc=$?
if [ $rc = 3 ] && [[ "$out" == *"verify: FAIL"* ]] && grep -q "^gsse-mesh: verify: " "$work/rot.err" && [ ! -e "$work/rot.vtu" ] && [ ! -e "$work/rot.stats.json" ]; then
  ok "--verify-tol 0 on a rotated cube: FAIL, exit 3, '$(head -c 80 "$work/rot.err")...', nothing written"
else bad "--verify-tol 0 on a rotated cube: exit $rc, files: $(ls "$work"/rot.* | tr '\n' ' ')"; fi
out=$("$mesh" "$work/rot.poly" --size 0.2 --verify -o "$work/rot.vtu" --stats "$work/rot.stats.json" 2>&1); rc=$?
if [ $rc = 0 ] && [[ "$out" == *"verify: PASS"* ]] && [ -e "$work/rot.vtu" ] && [ -e "$work/rot.stats.json" ]; then ok "--verify on the rotated cube: PASS, both files written"
else bad "--verify on the rotated cube: exit $rc"; fi

# --quality on a needle: where the elements are excepted, the round cap, the exception off
cat > "$work/needle.poly" <<'POLY'
13 3 0 0
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.5 0.5 4
6 -1 -1 -1
7 2 -1 -1
8 2 2 -1
9 -1 2 -1
10 -1 -1 5
11 2 -1 5
12 2 2 5
13 -1 2 5
11 0
1
4 1 2 3 4
1
3 1 2 5
1
3 2 3 5
1
3 3 4 5
1
3 4 1 5
1
4 6 7 8 9
1
4 10 11 12 13
1
4 6 7 11 10
1
4 7 8 12 11
1
4 8 9 13 12
1
4 9 6 10 13
0
2
1 0.5 0.5 0.5 1 0
2 -0.5 -0.5 -0.5 2 0
POLY
out=$("$mesh" "$work/needle.poly" --quality 2 --grade 1.3 --verify --stats "$work/n.json" 2>&1); rc=$?
verdict=$($py - "$work/n.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["quality"]["refinement"]
near = r["excepted_near"]
ok = r["converged"] and r["excepted"] > 0 and r["excepted"] == r["above_bound"] and len(near) == 1 \
     and near[0]["at"] == [0.5, 0.5, 4] and near[0]["elements"] == r["excepted"]
print("ok" if ok else "bad: %s" % r)
PY
)
if [ $rc = 0 ] && [ "$verdict" = ok ] && [[ "$out" == *"near the input point (0.5, 0.5, 4)"* ]]; then ok "--quality on the needle: excepted at the apex, in --stats and the summary"
else bad "--quality on the needle: exit $rc, $verdict"; fi
"$mesh" "$work/needle.poly" --quality 2 --grade 1.3 --quality-rounds 3 --stats "$work/n3.json" --quiet; rc=$?
verdict=$($py - "$work/n3.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["quality"]["refinement"]
rounds = r["per_round"]  # one record a round, adding up to the totals
ok = r["rounds"] == 3 and not r["converged"] and len(rounds) == 3 \
     and sum(x["inserted"] for x in rounds) == r["inserted"] and sum(x["boundary_splits"] for x in rounds) == r["boundary_splits"] \
     and sum(x["cavity_made"] for x in rounds) == r["cavity_made"] and all(x["bad"] > 0 for x in rounds) \
     and abs(sum(x["seconds"]["mesh"] for x in rounds) - r["seconds"]["mesh"]) <= 1e-5 * r["seconds"]["mesh"] + 1e-9
print("ok" if ok else r)
PY
)
if [ $rc = 0 ] && [ "$verdict" = ok ]; then ok "--quality-rounds 3: 3 rounds, not converged, each in --stats per_round"; else bad "--quality-rounds 3: exit $rc, $verdict"; fi
"$mesh" "$work/needle.poly" --quality 2 --grade 1.3 --quality-rounds 5 --acute-guard 0 --stats "$work/n0.json" --quiet; rc=$?
verdict=$($py -c "import json,sys; r=json.load(open(sys.argv[1]))['quality']['refinement']; print('ok' if r['excepted'] == 0 and r['excepted_near'] == [] and r['above_bound'] > 0 else r)" "$work/n0.json")
if [ $rc = 0 ] && [ "$verdict" = ok ]; then ok "--acute-guard 0: nothing excepted"; else bad "--acute-guard 0: exit $rc, $verdict"; fi

# --check: the good mesh, then broken copies of it
out=$("$mesh" "$work/box.poly" --check "$work/m.node" 2>&1); rc=$?
if [ $rc = 0 ] && [[ "$out" == *"check: PASS"* ]]; then ok "--check m.node: PASS, exit 0"; else bad "--check m.node: exit $rc: $out"; fi
cp "$work/m.node" "$work/d.node"; cp "$work/m.json" "$work/d.json" 2>/dev/null
$py - "$work/m.ele" "$work/d.ele" <<'PY'
import sys
lines = [l for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
head = lines[0].split()
head[0] = str(int(head[0]) - 1)
open(sys.argv[2], "w").write(" ".join(head) + "\n" + "".join(lines[1:-1]))
PY
err=$("$mesh" "$work/box.poly" --check "$work/d.node" 2>&1 >/dev/null); rc=$?
if [ $rc = 3 ] && [[ "$err" == *"check: "*"faces lie on no input facet"* ]]; then ok "--check, one tetrahedron dropped: exit 3, '$(echo "$err" | head -1)'"
else bad "--check, one tetrahedron dropped: exit $rc, '$err'"; fi
cp "$work/m.node" "$work/r.node"
awk 'NR > 1 && NF >= 6 && !/^#/ { $6 = 1 } { print }' "$work/m.ele" > "$work/r.ele"
err=$("$mesh" "$work/box.poly" --check "$work/r.node" 2>&1 >/dev/null); rc=$?
if [ $rc = 3 ] && [[ "$err" == *"region point"* ]]; then ok "--check, inner box relabelled: exit 3, '$(echo "$err" | head -1)'"
else bad "--check, inner box relabelled: exit $rc, '$err'"; fi
msg=$("$mesh" "$work/box.poly" --check "$work/m.node" -o "$work/x.vtu" 2>&1); rc=$?
if [ $rc = 2 ] && [ ! -e "$work/x.vtu" ]; then ok "--check with -o: exit 2"; else bad "--check with -o: exit $rc"; fi

# numbers: the whole value must be one, finite, the option named (stod took "0.2abc" as 0.2, "abc"
# failed as "stod", --max-steiner -1 wrapped round to a huge limit, --size 1e999 and inf were taken
# as infinite, --threads abc failed as "stol", --threads +4 was taken as 4)
for bad_arg in "--size 0.2abc:--size: '0.2abc' is not a finite number" "--grade abc:--grade: 'abc' is not a finite number" \
               "--size 1e999:--size: '1e999' is not a finite number" "--size inf:--size: 'inf' is not a finite number" \
               "--grade nan:--grade: 'nan' is not a finite number" "--threads abc:--threads: 'abc' is not a whole number" \
               "--threads 0:--threads must be a whole number from 1 to 4096" "--threads +4:--threads: '+4' is not a whole number" \
               "--quality 0.5:quality: the 3D bound is a radius-edge ratio of at least" \
               "--quality-rounds 3x:--quality-rounds: '3x' is not a whole number" "--max-steiner -1:--max-steiner must not be negative"; do
  opt=${bad_arg%%:*}; want=${bad_arg#*:}
  err=$("$mesh" "$work/box.poly" $opt -o "$work/n.vtu" 2>&1 >/dev/null); rc=$?
  if [ $rc = 2 ] && [[ "$err" == *"$want"* ]] && [ ! -e "$work/n.vtu" ]; then ok "$opt: exit 2, '$want'"; else bad "$opt: exit $rc, '$(echo "$err" | head -1)'"; fi
done

# overwrites: refused before any work, the files as they were
mkdir "$work/ow"
cp "$work/box.poly" "$work/ow/b.poly"
printf '{"segments": ["outer", "inner"], "sizes": {"inner": 0.1}}\n' > "$work/ow/b.json"
cp "$work/ow/b.json" "$work/ow/b.json.orig"
check_refused() {  # label, expected words in the message, gsse-mesh arguments...
  local label=$1 words=$2; shift 2
  local err rc
  err=$(cd "$work/ow" && "$mesh" "$@" --quiet 2>&1 >/dev/null); rc=$?
  if [ $rc = 1 ] && [[ "$err" == *"$words"* ]] && cmp -s "$work/ow/b.json" "$work/ow/b.json.orig" && [ ! -e "$work/ow/b.node" ] && [ ! -e "$work/ow/b.ele" ] && [ ! -e "$work/ow/g.ele" ] && [ ! -e "$work/ow/out.vtu" ]
  then ok "$label: exit 1, '$err'"; else bad "$label: exit $rc, '$err'"; fi
}
check_refused "-o b.node beside b.poly" "-o b.node's sidecar of segment names (b.json) would overwrite the input's sidecar" b.poly --size 0.2 -o b.node
check_refused "--stats b.json beside b.poly" "--stats b.json would overwrite the input's sidecar" b.poly --size 0.2 -o out.vtu --stats b.json
check_refused "--stats ./b.json (another spelling)" "would overwrite the input's sidecar" b.poly --size 0.2 -o out.vtu --stats "$work/ow/../ow/b.json"
check_refused "--stats g.json with -o g.node" "--stats g.json and -o g.node's sidecar of segment names would both write g.json" b.poly --size 0.2 -o g.node --stats g.json
check_refused "--plc-out onto the input" "--plc-out b.poly would overwrite the input" b.poly --plc-out b.poly
"$mesh" "$work/box.poly" --size 0.2 --quiet -o "$work/ow/c.node" || bad "c.node did not mesh"
check_refused "-o onto the --cloud file" "-o c.node would overwrite the --cloud file" b.poly --size 0.2 --cloud c.node -o c.node
ln "$work/ow/b.json" "$work/ow/h.json"
check_refused "--stats h.json, a hard link to the sidecar" "--stats h.json would overwrite the input's sidecar" b.poly --size 0.2 -o out.vtu --stats h.json
rm "$work/ow/h.json"
mkdir "$work/ow/bg"
cp "$work/box.poly" "$work/ow/bg/k.poly"
printf '{"background": "m.v1"}\n' > "$work/ow/bg/k.json"
cp "$work/ow/bg/k.json" "$work/ow/bg/k.json.orig"
err=$(cd "$work/ow/bg" && "$mesh" k.poly --grade 1.3 -o m.v1.node --quiet 2>&1 >/dev/null); rc=$?
if [ $rc = 1 ] && [[ "$err" == *"-o m.v1.node would overwrite the background mesh"* ]] && cmp -s "$work/ow/bg/k.json" "$work/ow/bg/k.json.orig" && [ ! -e "$work/ow/bg/m.v1.node" ]
then ok "-o onto the background mesh 'm.v1' (read as m.v1.node): exit 1, '$err'"; else bad "-o onto the background mesh 'm.v1': exit $rc, '$err'"; fi
for extra in "-o x.vtu" "--stats x.json" "--check b.node" "--size 0.2" "--verify" "--quality" "--rules r.rules" "--fill rules" "--max-steiner 5" "--no-feature-size" "--sliver-angle 5" "--msh 2.2"; do
  err=$(cd "$work/ow" && "$mesh" b.poly --plc-out p.poly $extra 2>&1 >/dev/null); rc=$?
  if [ $rc = 2 ] && [[ "$err" == *"--plc-out writes the input as read and meshes nothing"* ]] && [ ! -e "$work/ow/p.poly" ] && [ ! -e "$work/ow/x.vtu" ] && [ ! -e "$work/ow/x.json" ]
  then ok "--plc-out with $extra: exit 2"; else bad "--plc-out with $extra: exit $rc, '$err'"; fi
done
err=$(cd "$work/ow" && "$mesh" b.poly --plc-out p.poly --threads 2 --no-merge --quiet 2>&1 >/dev/null); rc=$?
if [ $rc = 0 ] && [ -s "$work/ow/p.poly" ]; then ok "--plc-out with --threads, --no-merge, --quiet: exit 0"; else bad "--plc-out with --threads, --no-merge, --quiet: exit $rc, '$err'"; fi
rm -f "$work/ow/p.poly" "$work/ow/p.json"
printf '{"points": 8, "segments": [{"name": "outer", "number": 1, "cells": 6}]}\n' > "$work/ow/s.json"
cp "$work/box.poly" "$work/ow/s.poly"
err=$(cd "$work/ow" && "$mesh" s.poly --size 0.2 -o out.vtu --quiet 2>&1 >/dev/null); rc=$?
if [ $rc = 1 ] && [[ "$err" == *"s.json:1:"*"as a gsse-mesh --stats file does"* ]] && [ ! -e "$work/ow/out.vtu" ]; then ok "a --stats file as a sidecar: exit 1, named"
else bad "a --stats file as a sidecar: exit $rc, '$err'"; fi
(cd "$work/ow" && "$mesh" b.poly --size 0.2 -o b1.node --stats b1.stats.json --quiet) && cmp -s "$work/ow/b.json" "$work/ow/b.json.orig" && [ -s "$work/ow/b1.ele" ] ||
  bad "b.poly -o b1.node --stats b1.stats.json: did not mesh, or the sidecar changed"
# --size-fit: quality.size_fit in --stats counts each segment's edges against the size at their
# midpoints (uniform --size here: 0.2); read back from the .node/.ele written (each segment's edges
# once, an interface edge in both), the counts must be the same; the summary says it; without a
# size it says there is none; --check takes no --size-fit
"$mesh" "$work/box.poly" --size 0.2 --size-fit --quiet -o "$work/fit.node" --stats "$work/fit.stats.json" || bad "--size-fit did not mesh"
got=$($py - "$work/fit" <<'PY'
import json, math, sys
base = sys.argv[1]
def rows(path):
    return [l.split() for l in open(path) if l.strip() and not l.lstrip().startswith("#")]
node = rows(base + ".node"); ele = rows(base + ".ele")
P = {int(r[0]): tuple(map(float, r[1:4])) for r in node[1:]}
edges = set()
for r in ele[1:]:
    v = list(map(int, r[1:5])); seg = r[5]
    for i in range(4):
        for j in range(i + 1, 4):
            edges.add((seg, min(v[i], v[j]), max(v[i], v[j])))
below = within = above = 0
for seg, u, v in edges:
    x = math.dist(P[u], P[v]) / 0.2
    below += x < 0.5; above += x > 1.5; within += 0.5 <= x <= 1.5
f = json.load(open(base + ".stats.json"))["quality"]["size_fit"]
mine = (len(edges), below, within, above)
theirs = (f["edges"], f["below_half"], f["within"], f["above"])
print("same" if mine == theirs and sum(h["edges"] for h in f["histogram"]) == f["edges"] else "read back %s, --stats %s" % (mine, theirs))
PY
)
if [ "$got" = same ]; then ok "--size-fit: quality.size_fit counts equal those read back from the mesh"; else bad "--size-fit: $got"; fi
out=$("$mesh" "$work/box.poly" --size 0.2 --size-fit -o "$work/fit2.vtu" 2>&1)
[[ "$out" == *"size fit: "*" edges against the size at their midpoints"* ]] && ok "--size-fit: the summary's line" || bad "--size-fit: no summary line"
out=$("$mesh" "$work/box.poly" --size-fit -o "$work/fit3.vtu" 2>&1)
[[ "$out" == *"size fit: no size to fit"* ]] && ok "--size-fit without a size: says so" || bad "--size-fit without a size: '$out'"
# the size rounds (3D, a size, no --quality): reported in the summary and --stats; off with
# --no-size-rounds
out=$("$mesh" "$work/box.poly" --size 0.2 -o "$work/sr.node" --stats "$work/sr.stats.json" 2>&1)
got=$(/usr/bin/python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))["quality"].get("refinement")
print("ok" if r and r["for"] == "size" and r["bound"] is None and r["converged"] and r["above_bound"] == 0 else r)' "$work/sr.stats.json")
[[ "$out" == *"size rounds (edges above 1.5 h"*"0 elements left with an edge above 1.5 h"* ]] && [ "$got" = ok ] \
  && ok "size rounds: in the summary and --stats (for: size, bound: null)" || bad "size rounds: '$got', '$out'"
out=$("$mesh" "$work/box.poly" --size 0.2 --no-size-rounds -o "$work/sr2.node" --stats "$work/sr2.stats.json" 2>&1)
got=$(/usr/bin/python3 -c '
import json, sys
print("none" if "refinement" not in json.load(open(sys.argv[1]))["quality"] else "there")' "$work/sr2.stats.json")
[[ "$out" != *"size rounds"* ]] && [ "$got" = none ] && ok "--no-size-rounds: no rounds" || bad "--no-size-rounds: '$got', '$out'"
err=$("$mesh" "$work/box.poly" --check "$work/fit.node" --size-fit 2>&1 >/dev/null); rc=$?
[ $rc = 2 ] && [[ "$err" == *"--size-fit"* ]] && ok "--check with --size-fit: exit 2" || bad "--check with --size-fit: exit $rc, '$err'"
# the allocator's settings: set by the run itself, left out on request, the user's own kept; the
# mesh the same under each
want=$(grep -o '"glibc[^"]*"' "$src/apps/allocator_tuning.hpp" | tr -d '"' | tr -d '\n')
# a sanitizer build keeps its sanitizer's allocator and starts once: nothing set
case "$(ldd "$mesh" 2>/dev/null)" in *libasan* | *libtsan*) want=None ;; esac
malloc_of() { $py -c 'import json, sys; print(json.load(open(sys.argv[1]))["malloc"])' "$1"; }
env -u GLIBC_TUNABLES -u LD_PRELOAD -u GSSE_MALLOC "$mesh" "$work/box.poly" --size 0.1 --quality 1.414 --threads 2 --quiet -o "$work/al1.node" --stats "$work/al1.stats.json"
GSSE_MALLOC=system env -u GLIBC_TUNABLES -u LD_PRELOAD "$mesh" "$work/box.poly" --size 0.1 --quality 1.414 --threads 1 --quiet -o "$work/al2.node" --stats "$work/al2.stats.json"
GLIBC_TUNABLES=glibc.malloc.top_pad=0 env -u LD_PRELOAD -u GSSE_MALLOC "$mesh" "$work/box.poly" --size 0.1 --quality 1.414 --threads 2 --quiet -o "$work/al3.node" --stats "$work/al3.stats.json"
got="$(malloc_of "$work/al1.stats.json") | $(malloc_of "$work/al2.stats.json") | $(malloc_of "$work/al3.stats.json")"
if [ -n "$want" ] && [ "$got" = "$want | None | glibc.malloc.top_pad=0" ]; then ok "allocator: --stats malloc by default, with GSSE_MALLOC=system, with the user's own: $got"
else bad "allocator: --stats malloc '$got', want '$want | None | glibc.malloc.top_pad=0'"; fi
same=yes
for k in 2 3; do for e in node ele face; do cmp -s "$work/al1.$e" "$work/al$k.$e" || same="no ($k.$e)"; done; done
[ "$same" = yes ] && [ "$(count "$work/al1.node")" -gt 100 ] && ok "allocator: the mesh is byte-identical under each" || bad "allocator: meshes differ: $same"
exit $fail
