#!/usr/bin/env bash
# The corpus of real surface inputs (tests/corpus/MANIFEST.tsv, made by make_corpus.py): every
# case is read as gsse-mesh reads it (--plc-out: the PLC with its region points), then meshed
# plain and with --size = bounding-box diagonal / 20, each with the library verifier under a
# timeout and, where ../shared exists, checked by meshcheck --inexact-ok. One line per run; the
# test fails if any run fails.
# usage: corpus_mesh.sh GSSE_MESH SOURCE_DIR [NAME...]
#   GSSE_CORPUS_TIMEOUT seconds per run (default 60), GSSE_CORPUS_JOBS cases at once (default 2)
#   GSSE_CORPUS_WORK keeps the inputs, meshes and logs in that folder (default: a temporary one)
set -uo pipefail
MESH=$1; src=$2; shift 2
here=$src/tests/corpus
# shellcheck source=corpus_lib.sh
source "$here/corpus_lib.sh"
TIMEOUT=${GSSE_CORPUS_TIMEOUT:-60}
JOBS=${GSSE_CORPUS_JOBS:-2}
if [ -n "${GSSE_CORPUS_WORK:-}" ]; then WORK=$GSSE_CORPUS_WORK; mkdir -p "$WORK"; else WORK=$(mktemp -d); trap 'rm -rf "$WORK"' EXIT; fi
find_meshcheck "$src"
names=(); files=()
while IFS=$'\t' read -r name file _; do
  [[ -z "$name" || "$name" == \#* || "$name" == name ]] && continue
  if [ $# -gt 0 ] && [[ " $* " != *" $name "* ]]; then continue; fi
  names+=("$name"); files+=("$file")
done < "$here/MANIFEST.tsv"
[ ${#names[@]} -gt 0 ] || { echo "FAIL: no corpus cases"; exit 1; }
mkdir -p "$WORK/inputs"
t0=$(date +%s.%N)
for k in "${!names[@]}"; do
  input=$WORK/inputs/${files[$k]}
  gzip -dc "$here/inputs/${files[$k]}.gz" > "$input" || { echo "FAIL: cannot unpack ${files[$k]}.gz"; exit 1; }
  mesh_case "${names[$k]}" "$input" &
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
done
wait
echo "corpus: ${#names[@]} cases, $JOBS at a time, $(seconds_since "$t0") s"
report "${names[@]}"
