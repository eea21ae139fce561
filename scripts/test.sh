#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. Tests that need ../shared skip visibly without it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build && ctest --output-on-failure -j "${GSSE_JOBS:-2}" ${GSSE_CTEST_ARGS:-}
