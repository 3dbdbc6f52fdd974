#!/usr/bin/env bash
# Configures and builds spallkit into ./build (Release, warnings on). Extra CMake args pass through.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
