#!/usr/bin/env bash
# The quality refinement round by round (--stats quality.refinement.per_round, issue 17): one
# benchmark structure at its 1e5 size with --quality BOUND, the fastest of REPEAT runs (by total
# stage seconds), one Markdown row a round: elements above the bound, circumcentres, splits, cells
# made, and the milliseconds of the round's plan, conformer, labelling and cavities; then the
# rounds' share of the steps' sum, first three and from the ninth on. Usage:
#   [ROTATE=1] [BOUND=1.414] [REPEAT=3] bench/quality_rounds.sh GSSE_MESH STRUCTURE [THREADS]
# (docs/benchmarks.md, fifty-sixth part: ROTATE=1 bench/quality_rounds.sh build/apps/gsse-mesh
# trench 2). Needs ../shared/bench/structures.py and /usr/bin/python3.
set -euo pipefail
G=${1:?usage: quality_rounds.sh GSSE_MESH STRUCTURE [THREADS]}
N=${2:?usage: quality_rounds.sh GSSE_MESH STRUCTURE [THREADS]}
T=${3:-2}
REPEAT=${REPEAT:-3}
BOUND=${BOUND:-1.414}
HERE=$(cd "$(dirname "$0")" && pwd)
GEN=${GSSE_SHARED_DIR:-$HERE/../../shared}/bench/structures.py
[ -f "$GEN" ] || { echo "needs $GEN" >&2; exit 2; }
. "$(cd "$(dirname "$0")" && pwd)/sizes.sh"  # SIZES, H
[ -n "${H[$N]:-}" ] || { echo "STRUCTURE is one of: ${!H[*]}" >&2; exit 2; }
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
flag=""; [ "${ROTATE:-0}" = 1 ] && flag=--rotate
/usr/bin/python3 "$GEN" "$N" --dim 3 $flag --out "$W" > /dev/null
for k in $(seq "$REPEAT"); do
  "$G" "$W/$N.poly" --size "${H[$N]}" --quality "$BOUND" --threads "$T" --quiet -o "$W/out.node" --stats "$W/run$k.stats.json"
done
/usr/bin/python3 - "$W" "$REPEAT" <<'PY'
import json, sys
w, repeat = sys.argv[1], int(sys.argv[2])
runs = [json.load(open(f"{w}/run{k}.stats.json")) for k in range(1, repeat + 1)]
best = min(runs, key=lambda d: sum(d["times"].values()))
r = best["quality"]["refinement"]
print(f"total {sum(best['times'].values()):.3f} s, quality stage {best['times']['quality']:.3f} s, "
      f"{r['rounds']} rounds, converged {r['converged']}")
print("| round | above the bound | circumcentres | splits | cells made | plan | conformer | labels | cavities |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
steps = ("plan", "conform", "label", "mesh")
for i, x in enumerate(r["per_round"], 1):
    s = x["seconds"]
    print(f"| {i} | {x['bad']:,} | {x['inserted']:,} | {x['boundary_splits']:,} | {x['cavity_made']:,} | "
          + " | ".join(f"{1e3 * s[k]:.1f}" for k in steps) + " |")
total = sum(sum(x["seconds"][k] for k in steps) for x in r["per_round"])
def share(rounds):
    return 100 * sum(sum(x["seconds"][k] for k in steps) for x in rounds) / total if total > 0 else 0
print(f"steps' sum {1e3 * total:.0f} ms: rounds 1-3 {share(r['per_round'][:3]):.0f}%, "
      f"rounds 9 on {share(r['per_round'][8:]):.0f}%")
PY
