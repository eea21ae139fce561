#!/usr/bin/env bash
# The library verifier against ../shared's independent meshcheck on the same files: the four
# benchmark structures (2D and 3D, at their suggested size) and the examples, meshed by the CLI
# with --verify, must pass both (and the verifier reading the written files back). The rotated
# MOSFET written as triangles must pass the verifier, and meshcheck in every check but one: it
# counts a face as spanning two coplanar facets of different markers when one of its vertices, a
# split point of the facets' common edge, is rounded 1e-17 across that edge (no double point can
# lie exactly on a slanted edge; docs/benchmarks.md). Exit 77 (ctest: skipped) without ../shared.
set -uo pipefail
mesh=$1; check=$2; src=$3
shared=${GSSE_SHARED_DIR:-$src/../shared}
if [ ! -f "$shared/bench/structures.py" ] || [ ! -x "$shared/tools/meshcheck/build.sh" ]; then
  echo "SKIPPED: ../shared absent (bench structures and meshcheck)"; exit 77
fi
MC=$(MESHCHECK_BUILD=${MESHCHECK_BUILD:-/tmp/meshcheck-build-gsse} "$shared/tools/meshcheck/build.sh" 2>/dev/null | tail -1)
[ -x "$MC" ] || { echo "FAIL: could not build meshcheck"; exit 1; }
py=/usr/bin/python3; [ -x $py ] || py=python3
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail=0
verdicts() {  # poly base -> "cli-verify meshcheck verifier" for files already written
  local mc mine
  mc=$("$MC" --inexact-ok "$1" "$2" | tail -1 | grep -o 'PASS\|FAIL')
  mine=$("$check" "$1" "$2" | tail -1 | grep -o 'PASS\|FAIL')
  echo "$mc $mine"
}
run() {  # label poly size
  local label=$1 poly=$2 h=$3 dir; dir=$(dirname "$poly")
  if ! "$mesh" "$poly" --size "$h" --verify --quiet -o "$dir/out.node"; then
    echo "FAIL: gsse-mesh --verify $label"; fail=1; return
  fi
  local v; v=$(verdicts "$poly" "$dir/out")
  printf '%-14s h=%-5s meshcheck/verifier: %s\n' "$label" "$h" "$v"
  [ "$v" = "PASS PASS" ] || fail=1
}
for s in mosfet diffusion trench finfet; do
  for d in 2 3; do
    dir=$work/$s$d; mkdir -p "$dir"
    $py "$shared/bench/structures.py" "$s" --dim $d --out "$dir" > /dev/null || { echo "FAIL: structures.py $s"; fail=1; continue; }
    h=$($py -c "import json;print(json.load(open('$dir/$s.json'))['h'])")
    run "$s ${d}D" "$dir/$s.poly" "$h"
  done
done
for e in mosfet stack mosfet2d; do
  mkdir -p "$work/ex_$e"; cp "$src/examples/$e".* "$work/ex_$e/"
  run "example $e" "$work/ex_$e/$e.poly" 0.1
done

# the rotated MOSFET as triangles: the same verdict from both checkers; the CLI's exit status and
# files follow the verifier's verdict
dir=$work/rot; mkdir -p "$dir"
$py "$shared/bench/structures.py" mosfet --rotate --triangles --out "$dir" > /dev/null
for h in "" 0.05; do
  "$mesh" "$dir/mosfet.poly" --quiet --verify ${h:+--size $h} -o "$dir/out.node" --stats "$dir/v.json" ||
    { echo "FAIL: gsse-mesh --verify rotated MOSFET ${h:+at $h}"; fail=1; continue; }
  [ -e "$dir/out.node" ] && [ -e "$dir/v.json" ] || { echo "FAIL: verified run wrote no files"; fail=1; }
  v=$(verdicts "$dir/mosfet.poly" "$dir/out"); echo "rotated MOSFET ${h:+at $h }meshcheck/verifier: $v"
  [ "${v#* }" = PASS ] || fail=1
  # meshcheck's failures, if any, are only the rounding artefact described above
  other=$("$MC" --inexact-ok "$dir/mosfet.poly" "$dir/out" | grep -E '^  [a-z].*: [0-9]+$' |
          grep -v 'informational\|spanning coplanar facets of different markers' |
          grep -E 'on no input facet|covered|more than one region|non-Delaunay elements [1-9]|inverted|duplicate' || true)
  [ -z "$other" ] || { echo "FAIL: meshcheck: $other"; fail=1; }
done
[ $fail = 0 ] && echo "verifier and meshcheck agree" || echo "verifier/meshcheck comparison FAILED"
exit $fail
