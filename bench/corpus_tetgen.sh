#!/usr/bin/env bash
# GSSE vs TetGen on the corpus (tests/corpus) and the rotated benchmark structures of ../shared:
# one markdown row per input: GSSE plain (conforming Delaunay, no size) and at the corpus size
# (bounding-box diagonal / 20), TetGen -pA (boundary recovery only; its output conforms but is
# not Delaunay in general) and -pq1.414A (quality) on the same PLC (gsse-mesh --plc-out).
# Columns: vertices, tetrahedra, Steiner points (vertices beyond the PLC's), wall seconds.
# Installs Debian's tetgen if missing. Single runs, 1 thread; timings drift 10-20% here.
# usage: bench/corpus_tetgen.sh [BUILD_DIR] [NAME...]    (names from MANIFEST.tsv or *_rot_*)
set -uo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}; shift || true
mesh=$build/apps/gsse-mesh
command -v tetgen >/dev/null || { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q tetgen >/dev/null; }
py=/usr/bin/python3; [ -x $py ] || py=python3
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
source "$here/tests/corpus/corpus_lib.sh"   # size_of
seconds_since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN{printf "%.2f", b-a}'; }
inputs=()
while IFS=$'\t' read -r name file _; do
  [[ -z "$name" || "$name" == \#* || "$name" == name ]] && continue
  gzip -dc "$here/tests/corpus/inputs/$file.gz" > "$work/$file"
  inputs+=("$name=$work/$file")
done < "$here/tests/corpus/MANIFEST.tsv"
shared=${GSSE_SHARED_DIR:-$here/../shared}
if [ -f "$shared/bench/structures.py" ]; then
  for s in mosfet diffusion trench finfet; do
    for t in "" --triangles; do
      d=$work/${s}_rot${t:+_tri}; mkdir -p "$d"
      $py "$shared/bench/structures.py" "$s" --rotate $t --out "$d" > /dev/null
      inputs+=("${s}_rot_3d${t:+_triangles}=$d/$s.poly")
    done
  done
fi
points_of() { awk 'NR == 1 || /^#/ {next} {print $1; exit}' "$1"; }
count() { awk '!/^#/ && NF {print $1; exit}' "$1"; }
echo "| input | PLC points | GSSE plain: verts / tets / Steiner / s | GSSE at size: verts / tets / Steiner / s | TetGen -pA: verts / tets / Steiner / s | TetGen -pq1.414A: verts / tets / Steiner / s |"
echo "|---|---|---|---|---|---|"
for item in "${inputs[@]}"; do
  name=${item%%=*}; input=${item#*=}
  if [ $# -gt 0 ] && [[ " $* " != *" $name "* ]]; then continue; fi
  poly=$work/$name.plc.poly  # not NAME.poly: its sidecar NAME.json is the input's, which gsse-mesh refuses to write
  "$mesh" "$input" --plc-out "$poly" > /dev/null 2>&1 || { echo "| $name | read error | | | | |"; continue; }
  np=$(count "$poly")
  size=$(size_of "$poly")
  gsse() {  # args...
    local t0; t0=$(date +%s.%N)
    if timeout 300 "$mesh" "$input" --quiet --threads 1 -o "$work/g.node" --stats "$work/g.stats" "$@" > /dev/null 2>&1; then
      local s; s=$(seconds_since "$t0")
      local v t
      v=$(count "$work/g.node"); t=$(count "$work/g.ele")
      echo "$v / $t / $((v - np)) / $s"
    else echo "fail"; fi
  }
  tg() {  # switches
    rm -f "$work"/t.1.*; cp "$poly" "$work/t.poly"
    local t0; t0=$(date +%s.%N)
    if timeout 300 tetgen "$1" -Q "$work/t.poly" > /dev/null 2>&1 && [ -f "$work/t.1.ele" ]; then
      local s; s=$(seconds_since "$t0")
      local v t
      v=$(count "$work/t.1.node"); t=$(count "$work/t.1.ele")
      echo "$v / $t / $((v - np)) / $s"
    else echo "fail"; fi
  }
  echo "| $name | $np | $(gsse) | $(gsse --size "$size") | $(tg -pA) | $(tg -pq1.414A) |"
done
