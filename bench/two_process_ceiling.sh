#!/usr/bin/env bash
# How much two cores of this machine give GSSE's workload at best: runs one single-threaded
# gsse-mesh alone, then two at once (independent processes, nothing shared), REPEAT times, and
# prints the throughput gain 2 * t_alone / t_pair (2.00 on two independent cores). A 1 -> 2 thread
# speed-up of the pipeline cannot exceed it.
# usage: bench/two_process_ceiling.sh [BUILD_DIR] [POLY] [H]   (default: build, the MOSFET, 0.0161)
set -euo pipefail
build=${1:-build}
shared=${GSSE_SHARED_DIR:-$(dirname "$0")/../../shared}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
poly=${2:-}
if [ -z "$poly" ]; then python3 "$shared/bench/structures.py" mosfet --dim 3 --out "$work" > /dev/null; poly=$work/mosfet.poly; fi
h=${3:-0.0161}
mesh() { "$build/apps/gsse-mesh" "$poly" --size "$h" --threads 1 --quiet -o "$work/$1.node"; }
now() { date +%s.%N; }
for i in $(seq "${REPEAT:-3}"); do
  t0=$(now); mesh a; t1=$(now)
  mesh b & mesh c; wait; t2=$(now)
  awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN{printf "alone %.2f s, pair %.2f s, gain %.2f\n", b-a, c-b, 2*(b-a)/(c-b)}'
done
