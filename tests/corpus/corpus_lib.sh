# Shared by corpus_mesh.sh and rotated_structures.sh (sourced): one case = one input meshed twice,
# plain and with --size, each by gsse-mesh with the library verifier under a timeout and, where
# ../shared has it, checked by the independent meshcheck against the PLC as gsse-mesh read it
# (--plc-out); and no mesh edge may be shorter than 1e-5 of the input's shortest edge (--stats
# "edges"). Every run prints one line: case, mode, vertices, tets, Steiner points, wall time,
# verdict. Needs: $MESH (gsse-mesh), $WORK (scratch folder), $MC (meshcheck or empty), $TIMEOUT.

# meshcheck from ../shared, built once into /tmp ($MC), and the same with the fixes of
# tests/support/meshcheck_fixed.py for its floating-point artefacts on slanted facets ($MCF);
# both empty (and a note) without ../shared
find_meshcheck() {  # src
  local shared=${GSSE_SHARED_DIR:-$1/../shared} py=/usr/bin/python3 fixed
  [ -x $py ] || py=python3
  MC=""; MCF=""
  if [ -x "$shared/tools/meshcheck/build.sh" ]; then
    MC=$(MESHCHECK_BUILD=${MESHCHECK_BUILD:-/tmp/meshcheck-build-gsse} "$shared/tools/meshcheck/build.sh" 2>/dev/null | tail -1)
    [ -x "$MC" ] || { echo "FAIL: could not build meshcheck"; exit 1; }
    fixed=${MESHCHECK_FIXED_SRC:-/tmp/meshcheck-fixed-gsse-src}
    $py "$1/tests/support/meshcheck_fixed.py" "$shared/tools/meshcheck" "$fixed" || { echo "FAIL: could not fix meshcheck"; exit 1; }
    MCF=$(MESHCHECK_BUILD=${MESHCHECK_FIXED_BUILD:-/tmp/meshcheck-fixed-gsse} sh "$fixed/build.sh" 2>/dev/null | tail -1)
    [ -x "$MCF" ] || { echo "FAIL: could not build the fixed meshcheck"; exit 1; }
  else
    echo "note: ../shared absent: gsse-mesh --verify only, no meshcheck"
  fi
}

seconds_since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}'; }

# Bounding-box diagonal of a .poly's points (TetGen 3D or Triangle 2D), /20
size_of() {  # poly
  awk '!/^[[:space:]]*#/ && NF { if (!n) { n = $1; d = $2; next } if (i < n) { i++
         for (k = 1; k <= d; k++) { x = $(k + 1); if (i == 1 || x < lo[k]) lo[k] = x; if (i == 1 || x > hi[k]) hi[k] = x } } }
       END { s = 0; for (k = 1; k <= d; k++) s += (hi[k] - lo[k]) ^ 2; printf "%.6g", sqrt(s) / 20 }' "$1"
}

# Meshes $input once; prints the result line and returns 0 for a pass.
mesh_once() {  # name input poly mode [gsse-mesh options...]
  local name=$1 input=$2 poly=$3 mode=$4; shift 4
  local dir=$WORK/$name/$mode; mkdir -p "$dir"
  local t0; t0=$(date +%s.%N)
  timeout -k 5 "$TIMEOUT" "$MESH" "$input" "$@" --verify --quiet -o "$dir/out.node" --stats "$dir/stats.json" \
    > "$dir/stdout" 2> "$dir/stderr"
  local rc=$? wall; wall=$(seconds_since "$t0")
  local verdict v=- t=- s=-
  case $rc in
    0) verdict=PASS ;;
    124) verdict="TIMEOUT (${TIMEOUT} s)" ;;
    1) verdict="ERROR: $(grep -m1 'error' "$dir/stderr" | sed "s|^gsse-mesh: error: ||; s|$input|${input##*/}|g" | cut -c1-160)" ;;
    3) verdict="VERIFY-FAIL: $(grep -m1 'verify:' "$dir/stderr" | sed 's/^gsse-mesh: verify: //' | cut -c1-160)" ;;
    *) verdict="CRASH (exit $rc): $(tail -1 "$dir/stderr" | cut -c1-120)" ;;
  esac
  if [ -f "$dir/stats.json" ]; then
    v=$(grep -o '"points": [0-9]*' "$dir/stats.json" | head -1 | grep -o '[0-9]*$')
    t=$(grep -o '"cells": [0-9]*' "$dir/stats.json" | awk '{s += $2} END {print s + 0}')
    s=$(grep -o '"steiner": [0-9]*' "$dir/stats.json" | grep -o '[0-9]*$')
  fi
  # no two points much closer than the input's own shortest edge: the closest the corpus has is
  # 4.9e-5 of it (occ_hammer at the diagonal / 20; 6.3e-5 at --quality 1.414, scad_example001);
  # before a rotation's image was kept off existing points, 2.4e-6 and 4.7e-7 (docs/benchmarks.md,
  # twenty-first part)
  if [ $rc = 0 ] && [ -f "$dir/stats.json" ]; then
    local ratio
    ratio=$(tr -d '\n' < "$dir/stats.json" | grep -o '"edges": {[^}]*}' | awk -F'[:,}]' '{ if ($5 > 0) printf "%.3g", $3 / $5 }')
    if [ -n "$ratio" ] && awk -v r="$ratio" 'BEGIN { exit !(r < 1e-5) }'; then
      verdict="POINTS TOO CLOSE: shortest edge $ratio of the input's shortest"
      rc=4
    fi
  fi
  if [ $rc = 0 ] && [ -n "$MC" ]; then
    # meshcheck as shipped; where it fails, the run passes only if the fixed meshcheck passes (the
    # fixes touch the facet placement of faces: conformity, and the regions it separates)
    local mc mcf; mc=$("$MC" --inexact-ok "$poly" "$dir/out" 2>&1 | tail -1)
    if [[ "$mc" == *PASS* ]]; then
      verdict="PASS (meshcheck PASS)"
    else
      mcf=$("$MCF" --inexact-ok "$poly" "$dir/out" 2>&1 | tail -1)
      if [[ "$mcf" == *PASS* ]]; then
        verdict="PASS (meshcheck: ${mc#meshcheck: } by rounding only; fixed meshcheck PASS)"
      else
        verdict="MESHCHECK-FAIL: $(echo "$mc" | cut -c1-100); fixed: $(echo "$mcf" | cut -c1-60)"
      fi
    fi
  fi
  printf '%-28s %-14s %8s %9s %7s %7s  %s\n' "$name" "$mode" "$v" "$t" "$s" "$wall" "$verdict"
  [[ "$verdict" == PASS* ]]
}

# Reads the input as a PLC into $WORK/NAME/plc.poly (--plc-out); if that fails, writes the
# READ-ERROR line and counts all `runs` of the case as failed, and returns 1.
read_case() {  # name input runs
  local name=$1 input=$2 runs=$3 dir=$WORK/$1
  mkdir -p "$dir"
  echo "$runs" > "$dir/runs"
  timeout -k 5 "$TIMEOUT" "$MESH" "$input" --plc-out "$dir/plc.poly" > "$dir/read.out" 2>&1 && return 0
  printf '%-28s %-14s %8s %9s %7s %7s  %s\n' "$name" "read" - - - - \
    "READ-ERROR: $(head -1 "$dir/read.out" | sed "s|^gsse-mesh: error: ||; s|$input|${input##*/}|g" | cut -c1-160)" > "$dir/result"
  echo "$runs" > "$dir/failed"
  return 1
}

# Reads the input as a PLC (--plc-out) and meshes it plain and at the bounding-box diagonal / 20,
# or at `size` when given. Writes its lines to $WORK/NAME/result and the number of failed runs to
# $WORK/NAME/failed.
mesh_case() {  # name input [size]
  local name=$1 input=$2 size=${3:-}
  local dir=$WORK/$name poly=$WORK/$name/plc.poly failed=0
  read_case "$name" "$input" 2 || return
  [ -n "$size" ] || size=$(size_of "$poly")
  {
    mesh_once "$name" "$input" "$poly" plain || failed=$((failed + 1))
    mesh_once "$name" "$input" "$poly" "size=$size" --size "$size" || failed=$((failed + 1))
  } > "$dir/result"
  echo $failed > "$dir/failed"
}

# Reads the input as a PLC and meshes it once with --grade G alone (graded sizing from the local
# feature size, no size given), checked as mesh_once's runs are. Writes $WORK/NAME/result and
# $WORK/NAME/failed.
graded_case() {  # name input grade
  local name=$1 input=$2 grade=$3 dir=$WORK/$1
  read_case "$name" "$input" 1 || return
  if mesh_once "$name" "$input" "$dir/plc.poly" "grade=$grade" --grade "$grade" > "$dir/result"; then echo 0 > "$dir/failed"; else echo 1 > "$dir/failed"; fi
}

print_header() {
  printf '%-28s %-14s %8s %9s %7s %7s  %s\n' case mode vertices tets steiner wall_s verdict
}

# Prints the results of the cases in the given order and the closing count; returns 1 if any failed.
report() {  # names...
  local runs=0 bad=0 n
  print_header
  for n in "$@"; do
    cat "$WORK/$n/result"
    runs=$((runs + $(cat "$WORK/$n/runs"))); bad=$((bad + $(cat "$WORK/$n/failed")))
  done
  echo "$((runs - bad)) passed, $bad failed"
  [ $bad = 0 ]
}

# Reads the input as a PLC and meshes it once with --quality BOUND (3D radius-edge): the run must
# pass as mesh_once's do (exit 0 with the library verifier, meshcheck where ../shared has it) and
# the refinement must have converged: every element above the bound excepted and counted (small
# input angles, the spacing floor; modules/refinement/README.md). Writes its lines to
# $WORK/NAME/result and 1 or 0 to $WORK/NAME/failed.
quality_case() {  # name input bound
  local name=$1 input=$2 bound=$3
  local dir=$WORK/$name poly=$WORK/$name/plc.poly line verdict py=/usr/bin/python3
  [ -x $py ] || py=python3
  read_case "$name" "$input" 1 || return
  # with GSSE_CORPUS_GRADE too: graded sizing from the local feature size and the bound together
  local mode="quality=$bound" extra=()
  [ -n "${GRADE:-}" ] && mode="quality=$bound,grade=$GRADE" && extra=(--grade "$GRADE")
  if line=$(mesh_once "$name" "$input" "$poly" "$mode" --quality "$bound" ${extra[@]+"${extra[@]}"}); then
    local sliver_free=0 inserted=0
    [ -z "${GRADE:-}" ] && [[ "${SLIVER_FREE:-}" == *" $name "* ]] && sliver_free=1
    [ -z "${GRADE:-}" ] && [[ "${INSERTED:-}" == *" $name "* ]] && inserted=1
    verdict=$($py - "$dir/$mode/stats.json" "$sliver_free" "$inserted" <<'PY'
import json, sys
q = json.load(open(sys.argv[1]))["quality"]
r, e, a = q["refinement"], q["edges"], q["angle"]
ok = r["converged"] and r["above_bound"] == r["excepted"]
if sys.argv[2] == "1" and a["below_5"] + a["above_170"] > 0:  # SLIVER_FREE (corpus_mesh.sh)
    print("SLIVERS: %d angles below 5 degrees, %d above 170: " % (a["below_5"], a["above_170"]), end="")
if sys.argv[3] == "1" and r.get("cavity_front_regions", 0) > 0:  # INSERTED (corpus_mesh.sh)
    print("FRONT-FILLED: a segment's cavities left to the front mesher %d times: " % r["cavity_front_regions"], end="")
# every round's cavities re-meshed in place: a round that falls back to meshing every segment
# whole is correct but is where a cavity went wrong (islands of surviving cells did, 14 rounds)
whole = r.get("full_remeshes", 0)
print(("" if ok else "NOT CONVERGED: ") + ("MESHED WHOLE %d times: " % whole if whole else "") +
      "%d rounds, %d above the bound, %d excepted (%d below the floor), shortest edge %.2g of the input's"
      % (r["rounds"], r["above_bound"], r["excepted"], r.get("below_floor", 0), e["shortest"] / e["shortest_input"]) +
      # circumcentres left out outside every segment, summed over the rounds (none on the corpus
      # at 1.414, 2026-11-29): shown when there are any
      (", %d circumcentres left out outside" % r["outside"] if r.get("outside", 0) else ""))
PY
)
    printf '%s\n%-28s %-14s %s\n' "$line" "" "" "$verdict" > "$dir/result"
    [[ "$verdict" == NOT* || "$verdict" == MESHED* || "$verdict" == SLIVERS* || "$verdict" == FRONT* ]] && echo 1 > "$dir/failed" || echo 0 > "$dir/failed"
  else
    echo "$line" > "$dir/result"
    echo 1 > "$dir/failed"
  fi
}
