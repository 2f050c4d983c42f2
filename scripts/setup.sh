#!/usr/bin/env bash
# scripts/setup.sh -- install every dependency of layers from Debian
# packages and build it (Release, Ninja, ccache) into ./build.
# (libgloo-dev: the Gloo headers c10d needs for data-parallel training.)
# Idempotent: installs only what is missing, rebuilds incrementally.
# Works as root or through sudo. Set LAYERS_BUILD_DIR to build elsewhere.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAYERS_BUILD_DIR:-$root/build}"

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libtorch-dev libgloo-dev libopenblas0-pthread
  libeigen3-dev libhdf5-dev libnanoflann-dev libspdlog-dev libyaml-cpp-dev libcli11-dev zlib1g-dev
  nlohmann-json3-dev gnuplot-nox libassimp-dev libcgal-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libjs-three chromium-headless-shell blender python3-numpy
  pybind11-dev python3-dev python3-torch python3-pytest
)

# Debian's `blender` (3.4.1) with python3-numpy (its glTF importer needs
# it): `layers crosscheck` re-simulates a stored sequence with Blender's
# cloth (docs/sim.md "Cross-check against Blender"), and the tests import
# `layers export --format glb` files into it (scripts/blender/). Those tests
# are skipped where CMake finds no blender.

if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

# LibTorch from Debian falls back to the reference BLAS unless an optimised
# one is selected (8x slower matmuls): prefer OpenBLAS (pthread build).
blas=/usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3
if [ -e "$blas" ] && command -v update-alternatives >/dev/null; then
  $sudo update-alternatives --set libblas.so.3-x86_64-linux-gnu "$blas" >/dev/null 2>&1 || true
  lapack=/usr/lib/x86_64-linux-gnu/openblas-pthread/liblapack.so.3
  [ -e "$lapack" ] && $sudo update-alternatives --set liblapack.so.3-x86_64-linux-gnu "$lapack" >/dev/null 2>&1 || true
fi

# The npm tools of the browser and glTF tests (tests/browser: puppeteer-core
# drives chromium-headless-shell through the report's viewer; the Khronos
# gltf-validator checks `layers export --format glb`), at the versions of
# its package-lock.json (node and npm come with the machine). Without npm
# or the registry the build goes on and
# those tests say they are skipped.
if command -v npm >/dev/null; then
  if [ ! -d "$root/tests/browser/node_modules/puppeteer-core" ] || [ ! -d "$root/tests/browser/node_modules/gltf-validator" ]; then
    (cd "$root/tests/browser" && npm ci --no-audit --no-fund --loglevel=error) ||
      echo "setup: npm ci in tests/browser failed: the browser and glTF validator tests will be skipped" >&2
  fi
else
  echo "setup: no npm: the browser and glTF validator tests will be skipped" >&2
fi

jobs="${LAYERS_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "$jobs"
echo "setup: built $build/bin/layers"
