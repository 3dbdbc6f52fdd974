#!/usr/bin/env bash
# Configures and builds spallkit into ./build (Release, warnings on). Extra CMake args pass through.
# Uses ccache when it is installed (faster rebuilds across build folders); SPALLKIT_BUILD_DIR sets
# the folder.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${SPALLKIT_BUILD_DIR:-build}
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Paths below the checkout hash relative to it, so another clone (CI's) reuses the objects.
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)"
