#!/usr/bin/env bash
# The main job on the built-in default scene: installs what is missing, builds, then runs the
# pipeline and writes everything under ./out (report.txt, report.json, plots/*.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
SPALL=build/apps/spall
OUT=${SPALLKIT_OUT:-out}
mkdir -p "$OUT/plots"

RECORD=datasets/samples/n205em_roller_defect_1200rpm.csv
echo "== diagnose $RECORD (N205EM, 1200 rpm)"
"$SPALL" diagnose "$RECORD" --bearing N205EM --rpm 1200 --plot-dir "$OUT/plots" | tee "$OUT/report.txt"
"$SPALL" diagnose "$RECORD" --bearing N205EM --rpm 1200 --json > "$OUT/report.json"
echo "== wrote $OUT/report.txt, $OUT/report.json and $OUT/plots/"
ls "$OUT/plots"
