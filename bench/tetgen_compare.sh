#!/usr/bin/env bash
# GSSE vs TetGen on the ../shared benchmark structures (3D). Installs Debian's tetgen if missing.
# usage: bench/tetgen_compare.sh [BUILD_DIR] [STRUCTURES...]   (default: build, mosfet diffusion trench finfet)
# For each structure and each size in SIZES (element size h giving GSSE about 1e5 and 6e5
# tetrahedra), runs gsse-mesh with 1 and 2 threads, then `tetgen -pq1.414Aa<vol>` with the volume
# bound calibrated (one untimed run) so that TetGen makes about as many tetrahedra as GSSE did.
# Every timed configuration runs REPEAT times (default 3), interleaved, and the fastest run is
# reported (this machine's timings vary by 10-20% from minute to minute). Prints one Markdown row
# per configuration: wall time, peak memory, elements, quality (radius-edge median/max, minimum
# dihedral angle), and the 1 -> 2 thread speed-up.
set -euo pipefail
build=${1:-build}; shift || true
structures=("${@:-mosfet diffusion trench finfet}")
shared=${GSSE_SHARED_DIR:-$(dirname "$0")/../../shared}
repeat=${REPEAT:-3}
command -v tetgen >/dev/null || { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q tetgen >/dev/null; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
. "$(cd "$(dirname "$0")" && pwd)/sizes.sh"  # SIZES, H
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
run() {  # command... ; prints "seconds peak_MB" (wall clock in ms: /usr/bin/time's %e has 10 ms steps)
  local t0=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$work/time" "$@" > "$work/log" 2>&1 || { echo "FAILED: $* (see below)" >&2; tail -3 "$work/log" >&2; return 1; }
  local t1=$EPOCHREALTIME
  awk -v a="$t0" -v b="$t1" '{printf "%.3f %.0f\n", b - a, $1/1024}' "$work/time"
}
best() {  # label command... ; runs REPEAT times, keeps "seconds peak_MB" of the fastest in $work/best.<label>
  local label=$1; shift
  local r; r=$(run "$@")
  if [ ! -f "$work/best.$label" ] || awk -v a="${r% *}" -v b="$(cut -d' ' -f1 "$work/best.$label")" 'BEGIN{exit !(a < b)}'; then
    echo "$r" > "$work/best.$label"
  fi
}
ele_count() { awk '$1 !~ /^#/ && NF {print $1; exit}' "$1"; }
echo "| structure | h | tool | threads | tetrahedra | wall s | peak MB | radius-edge median / max | min dihedral | speed-up 1->2 |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for s in ${structures[@]}; do
  python3 "$shared/bench/structures.py" "$s" --dim 3 --out "$work" > /dev/null
  for h in ${SIZES[$s]}; do
    rm -f "$work"/best.*
    for i in $(seq "$repeat"); do
      for t in 1 2; do best "g$t" "$build/apps/gsse-mesh" "$work/$s.poly" --size "$h" --threads "$t" --quiet -o "$work/g.node"; done
    done
    n=$(ele_count "$work/g.ele")
    read -r med mx dmin < <(quality "$work/g")
    read -r s1 m1 < "$work/best.g1"; read -r s2 m2 < "$work/best.g2"
    echo "| $s | $h | gsse | 1 | $n | $s1 | $m1 | $med / $mx | $dmin | |"
    echo "| $s | $h | gsse | 2 | $n | $s2 | $m2 | $med / $mx | $dmin | $(awk -v a="$s1" -v b="$s2" 'BEGIN{printf "%.2f", a/b}') |"
    # TetGen: calibrate the volume bound to GSSE's element count (untimed), then time it
    cp "$work/$s.poly" "$work/t.poly"
    vol=$(python3 -c "print(f'{$h**3/(6*2**0.5):.3g}')")
    tetgen -pq1.414Aa"$vol" -Q "$work/t.poly" > /dev/null
    vol=$(python3 -c "print(f'{$vol * $(ele_count "$work/t.1.ele") / $n:.3g}')")
    for i in $(seq "$repeat"); do best tg tetgen -pq1.414Aa"$vol" -Q "$work/t.poly"; done
    read -r st mt < "$work/best.tg"
    read -r med mx dmin < <(quality "$work/t.1")
    echo "| $s | $h | tetgen -pq1.414Aa$vol | 1 | $(ele_count "$work/t.1.ele") | $st | $mt | $med / $mx | $dmin | |"
  done
done
