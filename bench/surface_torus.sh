#!/usr/bin/env bash
# A part meshed from its surface: a torus (R 1, r 0.3) cut by a box into three volumes, its
# surfaces meshed by Gmsh (OpenCASCADE, python3-gmsh) with triangles of at most H (default 0.03:
# about 39,700 elements, 19,369 points). Times gsse-mesh on it plain (no interior point: every
# empty ball of the tube is large), with --size H and with --quality 1.414, 2 threads, against
# TetGen -p and -pq1.414 on the same PLC (gsse-mesh --plc-out). docs/benchmarks.md, sixty-second part.
# usage: bench/surface_torus.sh [BUILD_DIR] [H]
set -euo pipefail
build=${1:-build}; h=${2:-0.03}
bin="$build/apps/gsse-mesh"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$h" "$work/torus.msh" <<'PY'
import sys, gmsh
gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0)
occ = gmsh.model.occ
t = occ.addTorus(0, 0, 0, 1, 0.3)
b = occ.addBox(0.8, -0.2, -0.5, 0.6, 0.4, 1)
occ.fragment([(3, t)], [(3, b)])
occ.synchronize()
gmsh.option.setNumber("Mesh.CharacteristicLengthMax", float(sys.argv[1]))
gmsh.model.mesh.generate(2)
gmsh.write(sys.argv[2])
gmsh.finalize()
PY
echo "| run | wall s | peak MB | points | tetrahedra |"
echo "|---|---:|---:|---:|---:|"
for opt in "" "--size $h" "--quality 1.414"; do
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$work/mem" "$bin" "$work/torus.msh" $opt --threads 2 --quiet --stats "$work/s.json" -o "$work/m.node"
  t1=$EPOCHREALTIME
  /usr/bin/python3 - "$work/s.json" "gsse-mesh ${opt:-(plain)}" "$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b-a}')" "$(( $(cat "$work/mem") / 1024 ))" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
stages = ", ".join(f"{k} {v:.2f}" for k, v in d["times"].items() if v >= 0.05)
print(f"| {sys.argv[2]} ({stages}) | {sys.argv[3]} | {sys.argv[4]} | {d['points']} | {d['quality']['elements']} |")
PY
done
"$bin" "$work/torus.msh" --plc-out "$work/plc.poly" --quiet
command -v tetgen > /dev/null || { apt-get update -q > /dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q tetgen > /dev/null; }
for sw in -pQ -pq1.414Q; do
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$work/mem" tetgen "$sw" "$work/plc.poly" > /dev/null
  t1=$EPOCHREALTIME
  echo "| tetgen $sw | $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b-a}') | $(( $(cat "$work/mem") / 1024 )) | $(head -1 "$work/plc.1.node" | awk '{print $1}') | $(head -1 "$work/plc.1.ele" | awk '{print $1}') |"
  rm -f "$work"/plc.1.*
done
