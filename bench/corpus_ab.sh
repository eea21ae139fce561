#!/usr/bin/env bash
# Two gsse-mesh binaries on the real-geometry corpus (tests/corpus/inputs), one run each in turns:
# wall seconds and peak memory per input, their sums, and whether the two meshes are byte-identical.
# usage: bench/corpus_ab.sh OLD_BINARY NEW_BINARY [OPTIONS...]   (default options: --quality 1.414)
# 2 threads (THREADS=n to change). scad_linear_extrude is left out with --quality, as corpus_quality
# leaves it out (modules/refinement/README.md). docs/benchmarks.md, sixty-fourth part.
set -euo pipefail
old=$1; new=$2; shift 2
if [ $# -gt 0 ]; then opts=("$@"); else opts=(--quality 1.414); fi
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
echo "| input | old s | new s | old MB | new MB | identical |"
echo "|---|---:|---:|---:|---:|---|"
for f in "$here"/tests/corpus/inputs/*.gz; do
  name=$(basename "$f" .gz)
  case " ${opts[*]} " in *" --quality"*) [ "$name" = scad_linear_extrude.stl ] && continue ;; esac
  in="$work/in.${name##*.}"
  zcat "$f" > "$in"
  row="| ${name%.*} |"
  for b in old new; do
    bin=$old; [ $b = new ] && bin=$new
    t0=$EPOCHREALTIME
    /usr/bin/time -f "%M" -o "$work/mem" "$bin" "$in" "${opts[@]}" --threads "${THREADS:-2}" --quiet -o "$work/$b.node" > /dev/null 2>&1 || true
    t1=$EPOCHREALTIME
    eval "s_$b=\$(awk -v a=\"$t0\" -v b=\"$t1\" 'BEGIN{printf \"%.2f\", b - a}')"
    eval "m_$b=\$(( \$(tail -1 \"$work/mem\") / 1024 ))"
  done
  same=yes
  for e in node ele face edge; do
    if [ -e "$work/old.$e" ] || [ -e "$work/new.$e" ]; then cmp -s "$work/old.$e" "$work/new.$e" || same=no; fi
  done
  echo "$row $s_old | $s_new | $m_old | $m_new | $same |"
  rm -f "$work"/in.* "$work"/old.* "$work"/new.*
done | tee "$work/rows"
awk -F'|' '{a += $3; b += $4; if ($7 ~ /no/) d++} END {printf "| all | %.2f | %.2f | | | %d differ |\n", a, b, d}' "$work/rows"
