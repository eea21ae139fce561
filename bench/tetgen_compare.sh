#!/usr/bin/env bash
# GSSE vs TetGen on the ../shared benchmark structures (3D). Installs Debian's tetgen if missing.
# usage: bench/tetgen_compare.sh [BUILD_DIR] [STRUCTURES...]   (default: build, mosfet diffusion trench finfet)
# For each structure and each size in SIZES (element size h; pick sizes that give about 1e5 and
# 6e5 tetrahedra), runs gsse-mesh with 1 and 2 threads and `tetgen -pq1.414Aa<vol>` with vol = h^3/(6*sqrt(2))
# (the volume of a regular tetrahedron of edge h), and prints one Markdown table row per run:
# wall time, peak memory, elements, and quality (radius-edge median/max, minimum dihedral angle).
set -euo pipefail
build=${1:-build}; shift || true
structures=("${@:-mosfet diffusion trench finfet}")
shared=${GSSE_SHARED_DIR:-$(dirname "$0")/../../shared}
command -v tetgen >/dev/null || { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q tetgen >/dev/null; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
declare -A SIZES=([mosfet]="0.031 0.0172" [diffusion]="0.047 0.026" [trench]="0.0465 0.0256" [finfet]="0.0286 0.0158")
quality() {  # base of a .node/.ele mesh -> "median_re max_re min_dihedral"
  python3 - "$1" <<'PY'
import sys, math
base = sys.argv[1]
def rows(f):
    for l in open(f):
        l = l.split('#')[0].split()
        if l: yield l
it = rows(base + ".node"); n = int(next(it)[0]); P = {}
for _ in range(n):
    r = next(it); P[int(r[0])] = tuple(map(float, r[1:4]))
it = rows(base + ".ele"); m = int(next(it)[0]); R = []; dmin = 180.0
def sub(a, b): return (a[0]-b[0], a[1]-b[1], a[2]-b[2])
def dot(a, b): return a[0]*b[0]+a[1]*b[1]+a[2]*b[2]
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
for _ in range(m):
    r = next(it); v = [P[int(x)] for x in r[1:5]]
    u, w, z = sub(v[1], v[0]), sub(v[2], v[0]), sub(v[3], v[0])
    det = dot(u, cross(w, z))
    if det == 0: continue
    c = [(dot(u,u)*a + dot(w,w)*b + dot(z,z)*e) / (2*det) for a, b, e in zip(cross(w, z), cross(z, u), cross(u, w))]
    rad = math.sqrt(dot(c, c))
    sh = min(math.dist(v[i], v[j]) for i in range(4) for j in range(i+1, 4))
    R.append(rad / sh)
    for i in range(4):
        for j in range(i+1, 4):
            k, l = [x for x in range(4) if x not in (i, j)]
            e = sub(v[j], v[i]); n1 = cross(e, sub(v[k], v[i])); n2 = cross(e, sub(v[l], v[i]))
            d = math.degrees(math.acos(max(-1, min(1, dot(n1, n2) / math.sqrt(dot(n1, n1) * dot(n2, n2))))))
            dmin = min(dmin, d)
R.sort()
print(f"{R[len(R)//2]:.3f} {R[-1]:.3g} {dmin:.2f}")
PY
}
run() {  # label command... ; prints "seconds peak_MB"
  /usr/bin/time -f "%e %M" -o "$work/time" "$@" > "$work/log" 2>&1 || { echo "FAILED: $* (see below)"; tail -3 "$work/log"; return 1; }
  awk '{printf "%.2f %.0f\n", $1, $2/1024}' "$work/time"
}
echo "| structure | h | tool | threads | tetrahedra | wall s | peak MB | radius-edge median / max | min dihedral |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in ${structures[@]}; do
  python3 "$shared/bench/structures.py" "$s" --dim 3 --out "$work" > /dev/null
  for h in ${SIZES[$s]}; do
    for t in 1 2; do
      read -r sec mb < <(run "$build/apps/gsse-mesh" "$work/$s.poly" --size "$h" --threads "$t" --quiet -o "$work/g.node")
      read -r med mx dmin < <(quality "$work/g")
      n=$(head -1 "$work/g.ele" | grep -v '#' || sed -n 2p "$work/g.ele"); n=$(awk 'NR<=2 && $1 ~ /^[0-9]+$/ {print $1; exit}' "$work/g.ele")
      echo "| $s | $h | gsse | $t | $n | $sec | $mb | $med / $mx | $dmin |"
    done
    vol=$(python3 -c "print(f'{$h**3/(6*2**0.5):.3g}')")
    cp "$work/$s.poly" "$work/t.poly"
    read -r sec mb < <(run tetgen -pq1.414Aa"$vol" -Q "$work/t.poly")
    read -r med mx dmin < <(quality "$work/t.1")
    n=$(awk 'NR==1 {print $1}' "$work/t.1.ele")
    echo "| $s | $h | tetgen -pq1.414Aa$vol | 1 | $n | $sec | $mb | $med / $mx | $dmin |"
  done
done
