#!/usr/bin/env bash
# The size rounds (a size without --quality; pipeline options::size_rounds) against the
# placement alone (--no-size-rounds), on the benchmark structures axis-aligned and rotated. 3D
# (DIM=3, the default): a uniform --size at the structure's 1e5 size and --grade 1.3 from the
# feature size alone; 2D (DIM=2): --size 0.005, and --grade 1.3 with --size 0.02 and 0.005.
# For each: points, edges above 1.5 h and the longest (--size-fit, an untimed run), the rounds and
# points they inserted, the fastest of REPEAT timed runs (wall seconds, without --size-fit) and its
# peak memory. Usage:
#   [DIM=2] bench/size_rounds.sh GSSE_MESH [THREADS] [STRUCTURES...]     (REPEAT=3 by default)
# Needs ../shared/bench/structures.py and /usr/bin/python3.
set -euo pipefail
G=${1:?usage: size_rounds.sh GSSE_MESH [THREADS] [STRUCTURES...]}
T=${2:-2}
shift $(( $# < 2 ? $# : 2 ))
NAMES=${*:-mosfet diffusion trench finfet}
REPEAT=${REPEAT:-3}
DIM=${DIM:-3}
[ "$DIM" = 2 ] || [ "$DIM" = 3 ] || { echo "DIM is 2 or 3" >&2; exit 2; }
HERE=$(cd "$(dirname "$0")" && pwd)
GEN=${GSSE_SHARED_DIR:-$HERE/../../shared}/bench/structures.py
[ -f "$GEN" ] || { echo "needs $GEN" >&2; exit 2; }
. "$(cd "$(dirname "$0")" && pwd)/sizes.sh"  # SIZES, H
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
echo "| structure | sizing | rounds | points | above 1.5 h | longest | rounds | inserted + splits | wall s | peak MB |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
for n in $NAMES; do
  for turn in plain rotated; do
    mkdir -p "$W/$turn"
    flag=""; [ "$turn" = rotated ] && flag=--rotate
    /usr/bin/python3 "$GEN" "$n" --dim "$DIM" $flag --out "$W/$turn" > /dev/null
    if [ "$DIM" = 3 ]; then sizings=("--size ${H[$n]}" "--grade 1.3"); else sizings=("--size 0.005" "--size 0.02 --grade 1.3" "--size 0.005 --grade 1.3"); fi
    for sizing in "${sizings[@]}"; do
      for rounds in off on; do
        opt=(); [ $rounds = off ] && opt=(--no-size-rounds)
        # shellcheck disable=SC2086
        "$G" "$W/$turn/$n.poly" $sizing "${opt[@]}" --threads "$T" --quiet --size-fit -o "$W/m.node" --stats "$W/s.json"
        best=""; peak=""
        for _ in $(seq "$REPEAT"); do
          # shellcheck disable=SC2086
          /usr/bin/time -f "%e %M" -o "$W/t" "$G" "$W/$turn/$n.poly" $sizing "${opt[@]}" --threads "$T" --quiet -o "$W/m.node"
          read -r s m < "$W/t"
          if [ -z "$best" ] || awk -v a="$s" -v b="$best" 'BEGIN{exit !(a < b)}'; then best=$s; peak=$((m / 1024)); fi
        done
        /usr/bin/python3 - "$W/s.json" "$n $turn" "$sizing" "$rounds" "$best" "$peak" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); q = s["quality"]; f = q["size_fit"]; r = q.get("refinement", {})
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {s['points']:,} | {f['above']} | {f['ratio']['max']:.3f} | "
      f"{r.get('rounds', '')} | {r.get('inserted', 0) + r.get('boundary_splits', 0) if r else ''} | {sys.argv[5]} | {sys.argv[6]} |")
PY
      done
    done
  done
done
