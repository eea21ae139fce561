#!/usr/bin/env bash
# 1 -> 2 thread speed-up of the whole gsse-mesh job, measured in alternating pairs: each pair runs
# 1 thread then 2 threads back to back, so a slow minute of this machine slows both. Prints the
# fastest 1-thread over the fastest 2-thread run, and the quartiles of the per-pair ratios.
# usage: bench/thread_speedup.sh [BUILD_DIR] [STRUCTURE] [H] [PAIRS]   (default: build mosfet 0.0161 15)
set -euo pipefail
build=${1:-build}
structure=${2:-mosfet}
h=${3:-0.0161}
pairs=${4:-15}
shared=${GSSE_SHARED_DIR:-$(dirname "$0")/../../shared}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
python3 "$shared/bench/structures.py" "$structure" --dim 3 --out "$work" > /dev/null
python3 - "$build/apps/gsse-mesh" "$work/$structure.poly" "$h" "$pairs" "$work" <<'PY'
import subprocess, sys, time
exe, poly, h, pairs, work = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
def run(t):
    t0 = time.perf_counter()
    subprocess.run([exe, poly, "--size", h, "--threads", str(t), "--quiet", "-o", f"{work}/m.node"], check=True)
    return time.perf_counter() - t0
one, two = [], []
for _ in range(pairs):
    one.append(run(1))
    two.append(run(2))
r = sorted(a / b for a, b in zip(one, two))
q = lambda f: r[min(len(r) - 1, int(f * len(r)))]
print(f"{poly.split('/')[-1]} h={h}, {pairs} pairs: 1 thread {min(one):.3f} s, 2 threads {min(two):.3f} s (fastest); "
      f"speed-up fastest/fastest {min(one) / min(two):.2f}, per pair quartiles {q(0.25):.2f} / {q(0.5):.2f} / {q(0.75):.2f}")
PY
