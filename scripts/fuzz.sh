#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined) in build-fuzz/ and runs
# each for a given time (docs/RELIABILITY.md, "Fuzzing").
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     default: 600 s, every target
#   targets: csv_record hdf5_record scene diagnose
#
# Seeds: fuzz/corpus/<target>/ (in the repo). Inputs found while fuzzing: build-fuzz/corpus/<target>/;
# crashes: build-fuzz/crashes/<target>/ (rerun one with build-fuzz/fuzz/fuzz_<target> FILE); logs:
# build-fuzz/fuzz_<target>.log. The last lines of each log give the executions (stat::
# number_of_executed_units) and the corpus size. JOBS sets the build's parallelism (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(csv_record hdf5_record scene diagnose); fi
build=${SPALLKIT_FUZZ_BUILD_DIR:-build-fuzz}

launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSPALLKIT_FUZZ=ON -DSPALLKIT_BUILD_TESTS=OFF "${launcher[@]}" >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]/#/fuzz_}"

declare -A max_len=([csv_record]=8192 [hdf5_record]=16384 [scene]=4096 [diagnose]=65536)
status=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/crashes/$t"
  echo "== fuzz_$t for ${seconds} s"
  if ! "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -max_len="${max_len[$t]}" -timeout=30 \
      -rss_limit_mb=4096 -print_final_stats=1 -artifact_prefix="$build/crashes/$t/" \
      "$build/corpus/$t" "fuzz/corpus/$t" >"$build/fuzz_$t.log" 2>&1; then
    echo "   FINDING: see $build/fuzz_$t.log and $build/crashes/$t/"
    status=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+.*DONE" "$build/fuzz_$t.log" | sed 's/^/   /' || true
done
exit $status
