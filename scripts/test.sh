#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs the whole GoogleTest suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
