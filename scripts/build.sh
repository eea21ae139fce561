#!/usr/bin/env bash
# Installs dependencies (Debian packages), configures and builds GSSE into ./build (Release).
# usage: build.sh [TARGET...]   (default: everything, tests included)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${GSSE_CMAKE_ARGS:-} >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j "${GSSE_JOBS:-2}" "${targets[@]}"
