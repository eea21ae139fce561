#!/usr/bin/env bash
# Graded sizing on the benchmark structures (issue 17): each structure axis-aligned and rotated,
# meshed with --grade G from the local feature size alone (no --size), verified, with its stage
# times and quality from --stats. Usage:
#   bench/sizing_bench.sh GSSE_MESH [THREADS] [GRADE] [STRUCTURES...]
# QUALITY=B in the environment adds --quality B (modules/refinement): the column `refine` is then
# that stage's time and `rounds` its rounds (0 otherwise).
# Needs ../shared/bench/structures.py (the structures) and /usr/bin/python3.
set -euo pipefail
G=${1:?usage: sizing_bench.sh GSSE_MESH [THREADS] [GRADE] [STRUCTURES...]}
T=${2:-2}
GRADE=${3:-1.3}
shift $(( $# < 3 ? $# : 3 ))
NAMES=${*:-mosfet finfet diffusion trench}
HERE=$(cd "$(dirname "$0")" && pwd)
GEN=$HERE/../../shared/bench/structures.py
[ -f "$GEN" ] || { echo "needs $GEN" >&2; exit 2; }
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
printf "%-10s %-7s %9s %10s %9s %8s %8s %8s %8s %6s %8s %6s %6s %8s %s\n" structure turn points tetrahedra min_size sizing conform mesh refine rounds total "<5deg" ">170" max_re verify
for n in $NAMES; do
  for turn in plain rotated; do
    mkdir -p "$W/$turn"
    flag=""; [ "$turn" = rotated ] && flag=--rotate
    /usr/bin/python3 "$GEN" "$n" $flag --out "$W/$turn" > /dev/null
    rm -f "$W/s.json"
    set +e
    /usr/bin/time -f %e -o "$W/t" "$G" "$W/$turn/$n.poly" --grade "$GRADE" --threads "$T" --verify --quiet --stats "$W/s.json" ${QUALITY:+--quality "$QUALITY"} 2> "$W/err"
    rc=$?
    set -e
    v=PASS; [ $rc -eq 0 ] || v="FAIL($rc)"
    if [ ! -f "$W/s.json" ]; then echo "$n $turn $v: $(head -c 300 "$W/err")"; continue; fi
    /usr/bin/python3 - "$W/s.json" "$n" "$turn" "$(cat "$W/t")" "$v" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); t = s["times"]; q = s["quality"]
cells = sum(x["cells"] for x in s["segments"])
rounds = q.get("refinement", {}).get("rounds", 0)
print(f"{sys.argv[2]:<10} {sys.argv[3]:<7} {s['points']:>9} {cells:>10} {q['min_size']:>9.3g} {t.get('sizing',0):>8.2f} "
      f"{t['conform']:>8.2f} {t['mesh']:>8.2f} {t.get('quality',0):>8.2f} {rounds:>6} {float(sys.argv[4]):>8.2f} {q['angle']['below_5']:>6} {q['angle']['above_170']:>6} "
      f"{q['radius_edge']['max']:>8.3g} {sys.argv[5]}")
PY
  done
done
