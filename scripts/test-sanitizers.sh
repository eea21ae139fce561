#!/usr/bin/env bash
# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer: a second build in
# ./build-san (-O1 -g, assertions on, every UB report fatal) and its ctest run. The libFuzzer
# tests are left out (their targets are sanitizer builds of their own, run by scripts/test.sh), and
# so are the install and Python tests (a consumer or an interpreter built without the sanitizers
# cannot load their libraries);
# everything else runs, the corpus too, with a longer per-run timeout (the sanitizers cost 2-4x).
# GSSE_SAN_CTEST_ARGS adds ctest arguments (e.g. "-LE corpus" locally).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DGSSE_SANITIZE=ON -DGSSE_FUZZ=OFF -DGSSE_BENCH=OFF -DGSSE_PYTHON=OFF >/dev/null
cmake --build build-san -j "${GSSE_JOBS:-2}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export GSSE_CORPUS_TIMEOUT=${GSSE_CORPUS_TIMEOUT:-300}
cd build-san && ctest --output-on-failure -j "${GSSE_JOBS:-2}" -LE "fuzz|install|python" ${GSSE_SAN_CTEST_ARGS:-}
