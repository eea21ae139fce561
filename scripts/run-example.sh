#!/usr/bin/env bash
# Sets up, builds and runs the main job: meshes the bundled MOSFET example (7 segments) at element
# size 0.05 with 2 threads, verifies the mesh and writes mosfet.vtu and its boundary faces, mosfet.boundary.vtu (open them
# in ParaView).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh gsse-mesh  # only the CLI and the libraries it needs, not the tests
./build/apps/gsse-mesh examples/mosfet.poly --size 0.05 --threads 2 --verify -o mosfet.vtu "$@"
