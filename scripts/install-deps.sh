#!/usr/bin/env bash
# Installs every Debian package GSSE needs to build, test and benchmark.
# Idempotent; needs root (or sudo). Set GSSE_SKIP_APT=1 to skip (e.g. on a non-Debian machine).
set -euo pipefail
[ "${GSSE_SKIP_APT:-0}" = 1 ] && exit 0
pkgs=(build-essential cmake ninja-build libcgal-dev libgmp-dev libmpfr-dev libboost-dev libboost-test-dev
      libmetis-dev zlib1g-dev python3 python3-meshio python3-numpy python3-gmsh python3-dev python3-pybind11 clang libclang-rt-14-dev)
missing=()
for p in "${pkgs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
