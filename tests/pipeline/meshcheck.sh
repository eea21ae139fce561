#!/usr/bin/env bash
# Meshes every ../shared/bench structure (2D and 3D, at its suggested size h) and the diffusion
# structure with a 1e4-point cloud, with the library verifier on, and requires the independent
# checker ../shared/tools/meshcheck to report PASS (valid, conforming, regions, Delaunay).
# Then a few structures again with interior points created by the front rules (--fill rules).
# Exit 77 (ctest: skipped) when ../shared is absent, as in a user's clone.
set -uo pipefail
mesh=$1; src=$2
shared=${GSSE_SHARED_DIR:-$src/../shared}
if [ ! -f "$shared/bench/structures.py" ] || [ ! -x "$shared/tools/meshcheck/build.sh" ]; then
  echo "SKIPPED: ../shared absent (bench structures and meshcheck)"; exit 77
fi
MC=$(MESHCHECK_BUILD=${MESHCHECK_BUILD:-/tmp/meshcheck-build-gsse} "$shared/tools/meshcheck/build.sh" 2>/dev/null | tail -1)
[ -x "$MC" ] || { echo "FAIL: could not build meshcheck"; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail=0; n=0; flags=()
run() {  # name dim extra-args...
  local name=$1 dim=$2; shift 2
  local dir=$work/$name$dim; mkdir -p "$dir"
  python3 "$shared/bench/structures.py" "$name" --dim "$dim" --out "$dir" "$@" > /dev/null || { echo "FAIL: structures.py $name"; fail=1; return; }
  local h; h=$(python3 -c "import json,sys;print(json.load(open('$dir/$name.json'))['h'])")
  local cloud=(); [ -f "$dir/$name.cloud.node" ] && cloud=(--cloud "$dir/$name.cloud.node")
  local t0=$(date +%s.%N)
  if ! "$mesh" "$dir/$name.poly" --size "$h" "${cloud[@]}" "${flags[@]}" --verify --quiet -o "$dir/out.node"; then
    echo "FAIL: gsse-mesh $name ${dim}D ${flags[*]}"; fail=1; return
  fi
  local verdict; verdict=$("$MC" "$dir/$name.poly" "$dir/out" | tail -1)
  n=$((n + 1))
  printf '%-10s %dD h=%-6s %-14s %s  (%s s)\n' "$name" "$dim" "$h" "${flags[*]}" "$verdict" "$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}')"
  [[ "$verdict" == *PASS* ]] || fail=1
}
for s in mosfet diffusion trench finfet; do for d in 2 3; do run $s $d; done; done
run diffusion 3 --cloud 10000
flags=(--fill rules)
for s in mosfet trench; do for d in 2 3; do run $s $d; done; done
[ $fail = 0 ] && echo "$n passed, 0 failed" || echo "meshcheck: some structures FAILED"
exit $fail
