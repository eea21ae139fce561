#!/usr/bin/env bash
# Builds gsse-mesh and draws the pictures of docs/images from its own output (scripts/pictures.py).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${GSSE_SKIP_APT:-0}" != 1 ] && ! dpkg -s python3-matplotlib >/dev/null 2>&1; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -q && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends python3-matplotlib
fi
bash scripts/build.sh gsse-mesh
/usr/bin/python3 scripts/pictures.py build/apps/gsse-mesh docs/images
