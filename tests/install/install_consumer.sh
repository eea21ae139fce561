#!/usr/bin/env bash
# `cmake --install` of this build into a scratch prefix, then a consumer project outside the source
# tree finds it with find_package(gsse CONFIG REQUIRED), builds against gsse::mesher and
# gsse::core, and meshes the bundled MOSFET: same point and cell counts as the installed gsse-mesh,
# verified.
# usage: install_consumer.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
for f in lib/cmake/gsse/gsseConfig.cmake lib/cmake/gsse/gsseTargets.cmake bin/gsse-mesh include/gsse/gsse.hpp \
         include/gsse/pipeline/pipeline.hpp share/doc/gsse/LICENSE; do
  [ -e "$tmp/prefix/$f" ] || { echo "FAIL: $f not installed"; exit 1; }
done
cp -r "$src/tests/install/consumer" "$tmp/consumer"
cmake -S "$tmp/consumer" -B "$tmp/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" > "$tmp/configure.log" ||
  { cat "$tmp/configure.log"; echo "FAIL: find_package(gsse) did not configure"; exit 1; }
cmake --build "$tmp/build" -j 1 > "$tmp/build.log" || { tail -30 "$tmp/build.log"; echo "FAIL: consumer did not build"; exit 1; }
"$tmp/build/core_only"
got=$("$tmp/build/consumer" "$src/examples/mosfet.poly" 0.1)
want=$("$tmp/prefix/bin/gsse-mesh" "$src/examples/mosfet.poly" --size 0.1 --stats "$tmp/s.json" --quiet &&
       /usr/bin/python3 -c "import json; d=json.load(open('$tmp/s.json')); print(d['points'], sum(s['cells'] for s in d['segments']), 0)")
echo "consumer: $got; installed gsse-mesh: $want"
[ "$got" = "$want" ] || { echo "FAIL: the consumer's mesh differs"; exit 1; }
# the Python module, installed beside the libraries
if [ -d "$build/python" ]; then
  py=$(ls "$tmp/prefix"/lib/python3/dist-packages/gsse*.so 2>/dev/null | head -1)
  [ -n "$py" ] || { echo "FAIL: the Python module was not installed"; exit 1; }
  n=$(cd "$tmp" && PYTHONPATH="$tmp/prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
      "import gsse; print(len(gsse.mesh_file('$src/examples/mosfet.poly', size=0.1).points))")
  [ "$n" = "${got%% *}" ] || { echo "FAIL: the installed Python module gives $n points"; exit 1; }
  echo "installed Python module: $n points"
fi
echo "ok"
