#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs the whole GoogleTest suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
# ctest runs two tests at a time and some tests use two OpenMP threads: threads that wait
# passively leave the cores to the other test instead of spinning on them.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-PASSIVE}
ctest --output-on-failure -j"$(nproc)" --timeout 900
