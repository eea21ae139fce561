#!/usr/bin/env bash
# Random-PLC stress test: for a fixed list of seeds, tests/stress/random_plc.py writes a PLC
# (rotated box unions with quadrilateral or triangle facets, triangulated surfaces with
# near-degenerate ties, thin layers 1e-8..1e-5 of the model; and bad input: overlapping boxes,
# piercing facets) and gsse-mesh meshes it with the library verifier under a timeout. A valid
# case passes if it is meshed and verified (and, where ../shared has meshcheck, meshcheck passes,
# as in the corpus tests); a bad one if it is rejected with a clear error (exit 1, a "gsse-mesh:
# error: FILE..." line naming the input, no output file). A timeout, a crash, a verify failure,
# a valid case rejected or a bad one meshed fails the test.
# usage: stress.sh GSSE_MESH SOURCE_DIR [FIRST_SEED [COUNT]]
#   GSSE_STRESS_TIMEOUT seconds per case (default 60); GSSE_CORPUS_WORK keeps the files;
#   GSSE_STRESS_ARGS options added to every run (e.g. "--quality 1.414", "--grade 1.3"). With
#   --quality or --grade a thin-layer case (seed % 5 == 3: layers 1e-8..1e-5 of the model) must
#   be rejected instead, saying its features are far below the model's size: no mesh could meet
#   the bound or the feature size there (docs/benchmarks.md, thirty-first part)
set -uo pipefail
MESH=$1; src=$2; first=${3:-0}; count=${4:-100}
here=$src/tests/stress
# shellcheck source=../corpus/corpus_lib.sh
source "$src/tests/corpus/corpus_lib.sh"
TIMEOUT=${GSSE_STRESS_TIMEOUT:-60}
py=/usr/bin/python3; [ -x $py ] || py=python3
if [ -n "${GSSE_CORPUS_WORK:-}" ]; then WORK=$GSSE_CORPUS_WORK; mkdir -p "$WORK"; else WORK=$(mktemp -d); trap 'rm -rf "$WORK"' EXIT; fi
find_meshcheck "$src"
bad=0 meshed=0 rejected=0
t0=$(date +%s.%N)
for ((s = first; s < first + count; ++s)); do
  input=$($py "$here/random_plc.py" "$s" "$WORK/case$s") || { echo "FAIL: random_plc.py $s"; bad=$((bad + 1)); continue; }
  out=$WORK/case$s.out
  rm -f "$out".node "$out".ele
  t=$(date +%s.%N)
  # shellcheck disable=SC2086
  timeout -k 5 "$TIMEOUT" "$MESH" "$input" ${GSSE_STRESS_ARGS:-} --verify --quiet -o "$out.node" > "$WORK/case$s.stdout" 2> "$WORK/case$s.stderr"
  rc=$?
  wall=$(seconds_since "$t")
  msg=$(grep -m1 'error\|verify:' "$WORK/case$s.stderr" | cut -c1-200)
  verdict=""
  case $rc in
    0)
      meshed=$((meshed + 1))
      verdict=PASS
      if [ -n "$MC" ]; then
        poly=$input
        if [[ "$input" != *.poly ]]; then poly=$WORK/case$s.plc.poly; "$MESH" "$input" --plc-out "$poly" > /dev/null 2>&1; fi
        mc=$("$MC" --inexact-ok "$poly" "$out" 2>&1 | tail -1)
        if [[ "$mc" != *PASS* ]]; then
          mcf=$("$MCF" --inexact-ok "$poly" "$out" 2>&1 | tail -1)
          [[ "$mcf" == *PASS* ]] && verdict="PASS (meshcheck: ${mc#meshcheck: } by rounding only; fixed meshcheck PASS)" ||
            verdict="FAIL: meshcheck: $mc; fixed: $mcf"
        fi
      fi ;;
    1)
      rejected=$((rejected + 1))
      if [[ "$msg" == "gsse-mesh: error: $input"* ]] && [ ! -e "$out.node" ]; then verdict="REJECTED (clear error): ${msg#gsse-mesh: error: }"
      else verdict="FAIL: exit 1 without a clear error naming the file, or with an output file: $msg"; fi ;;
    124) verdict="FAIL: TIMEOUT (${TIMEOUT} s)" ;;
    3) verdict="FAIL: VERIFY: $msg" ;;
    *) verdict="FAIL: CRASH (exit $rc): $(tail -1 "$WORK/case$s.stderr" | cut -c1-160)" ;;
  esac
  beyond=0  # a thin layer asked for a quality bound or a feature size: to be rejected
  if [ $((s % 5)) = 3 ] && [[ " ${GSSE_STRESS_ARGS:-} " == *" --quality "* || " ${GSSE_STRESS_ARGS:-} " == *" --grade "* ]]; then beyond=1; fi
  if [[ "$input" == *_bad.poly && $rc = 0 ]]; then verdict="FAIL: bad input (overlapping or piercing facets) was meshed"; fi
  if [ $beyond = 1 ] && [ $rc = 0 ]; then verdict="FAIL: a layer far below the model's size was meshed with $GSSE_STRESS_ARGS"; meshed=$((meshed - 1)); fi
  if [ $beyond = 1 ] && [ $rc = 1 ] && [[ "$verdict" == REJECTED* ]] && ! grep -q "features far below the model's size" "$WORK/case$s.stderr"; then
    verdict="FAIL: rejected without naming features far below the model's size: ${msg#gsse-mesh: error: }"
  fi
  if [[ "$input" != *_bad.poly && $beyond = 0 && $rc = 1 ]]; then verdict="FAIL: valid input rejected: ${msg#gsse-mesh: error: }"; fi
  [[ "$verdict" == FAIL* ]] && bad=$((bad + 1))
  printf 'seed %-4s %-10s %6s s  %s\n' "$s" "${input##*.}" "$wall" "$verdict"
done
echo "stress${GSSE_STRESS_ARGS:+ $GSSE_STRESS_ARGS}: $count cases from seed $first in $(seconds_since "$t0") s: $meshed meshed and verified, $rejected rejected, $bad failed"
[ $bad = 0 ]
