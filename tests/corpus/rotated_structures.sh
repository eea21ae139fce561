#!/usr/bin/env bash
# The benchmark structures of ../shared/bench/structures.py turned by a generic rotation (no facet
# parallel to an axis, points coplanar only up to rounding): mosfet, diffusion, trench, finfet, in
# 2D, in 3D with quadrilateral facets and in 3D with triangle facets (--triangles; in 2D it changes
# nothing). Each is meshed plain and at the structure's h (its .json) with the library verifier
# and checked by meshcheck --inexact-ok, as the corpus cases are (corpus_lib.sh). Exit 77 (ctest:
# skipped) without ../shared.
# usage: rotated_structures.sh GSSE_MESH SOURCE_DIR
#   GSSE_CORPUS_TIMEOUT seconds per run (default 60), GSSE_CORPUS_JOBS cases at once (default 2)
#   GSSE_CORPUS_WORK keeps the inputs, meshes and logs in that folder (default: a temporary one)
set -uo pipefail
MESH=$1; src=$2
shared=${GSSE_SHARED_DIR:-$src/../shared}
if [ ! -f "$shared/bench/structures.py" ]; then echo "SKIPPED: ../shared absent (bench structures and meshcheck)"; exit 77; fi
# shellcheck source=corpus_lib.sh
source "$src/tests/corpus/corpus_lib.sh"
TIMEOUT=${GSSE_CORPUS_TIMEOUT:-60}
JOBS=${GSSE_CORPUS_JOBS:-2}
if [ -n "${GSSE_CORPUS_WORK:-}" ]; then WORK=$GSSE_CORPUS_WORK; mkdir -p "$WORK"; else WORK=$(mktemp -d); trap 'rm -rf "$WORK"' EXIT; fi
find_meshcheck "$src"
[ -n "$MC" ] || { echo "FAIL: meshcheck missing in $shared"; exit 1; }
PY=/usr/bin/python3; [ -x $PY ] || PY=python3
names=()
t0=$(date +%s.%N)
for s in mosfet diffusion trench finfet; do
  for variant in 2d 3d 3d_triangles; do
    name=${s}_rot_$variant; dir=$WORK/gen/$name; args=(--rotate --out "$dir")
    case $variant in 2d) args+=(--dim 2) ;; 3d) args+=(--dim 3) ;; 3d_triangles) args+=(--dim 3 --triangles) ;; esac
    $PY "$shared/bench/structures.py" "$s" "${args[@]}" > /dev/null || { echo "FAIL: structures.py $s ${args[*]}"; exit 1; }
    h=$($PY -c "import json; print(json.load(open('$dir/$s.json'))['h'])")
    names+=("$name")
    mesh_case "$name" "$dir/$s.poly" "$h" &
    while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
  done
done
wait
echo "rotated structures: ${#names[@]} cases, $JOBS at a time, $(seconds_since "$t0") s"
report "${names[@]}"
