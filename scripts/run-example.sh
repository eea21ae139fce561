#!/usr/bin/env bash
# Sets up, builds and runs the main job on the bundled MOSFET example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/apps/gsse-mesh examples/mosfet.poly "$@"
