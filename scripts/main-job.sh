#!/usr/bin/env bash
# The main job on the built-in default scene: installs what is missing, builds, then runs the
# pipeline and writes everything under ./out:
#   1. `spall simulate` the paper's verification scene (N205EM, 10 kN, one 1.38 x 0.59 mm roller
#      spall, 1200 rpm) with the hybrid model (rigid rollers/cage/inner ring, FE outer ring +
#      adapter) on a coarse 2 mm housing mesh, 1 s: out/run.h5 (+ out/run.csv);
#   2. `spall diagnose` on the simulated acceleration from 0.05 s on (past the start-up):
#      out/report.txt, out/report.json, out/plots/*.png;
#   3. `spall identify` on the same record (number of spalled rollers, positions, width or why
#      not): out/identify.txt, out/identify.json;
#   4. the same diagnosis of the bundled sample record: out/sample_report.txt/.json.
# SPALLKIT_SIM_SETS overrides the simulation settings (e.g. a finer mesh or longer run);
# SPALLKIT_SPALL=path/to/spall runs the pipeline with an already built binary (no install, no
# build: for checking the job from one's own build folder); SPALLKIT_OUT sets the folder.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z "${SPALLKIT_SPALL:-}" ]]; then
  bash scripts/install-deps.sh
  bash scripts/build.sh
fi
SPALL=${SPALLKIT_SPALL:-build/apps/spall}
OUT=${SPALLKIT_OUT:-out}
mkdir -p "$OUT/plots"

# The scene's own speed (1200 rpm, the paper's) for 1 s (8.3 cage turns, 1 Hz resolution): about
# a minute of simulation (docs/PERFORMANCE.md). The paper's friction (mu 0.01 / 0.005, the scene's)
# with the lubricant traction law on the roller-race contacts (friction.model = "ehl",
# docs/CONTACT.md "Lubricant traction"): with Coulomb at mu 0.01 alone the rigid defective roller
# is trapped on its spall corners at its first loaded spall passage (docs/PAPER.md, "The main
# job").
RPM=1200
SETS=${SPALLKIT_SIM_SETS:-"--set model.fidelity=hybrid --set mesh.size_mm=2.0 \
  --set operation.speed_rpm=$RPM --set run.duration_s=1.0 --set friction.model=ehl"}
echo "== simulate datasets/scenes/paper-verification.toml ($SETS)"
# shellcheck disable=SC2086
time "$SPALL" simulate datasets/scenes/paper-verification.toml -o "$OUT/run.h5" --csv "$OUT/run.csv" \
  $SETS | tee "$OUT/simulate.txt"
# The first 0.05 s (the 5 ms ramps and the rollers settling) are left out of the diagnosis: their
# spikes would dominate the squared envelope (docs/DIAGNOSIS.md, "Empirical false-alarm rate").
FROM=0.05
echo "== diagnose $OUT/run.csv from $FROM s (N205EM, $RPM rpm)"
"$SPALL" diagnose "$OUT/run.csv" --bearing N205EM --rpm "$RPM" --from-s $FROM --plot-dir "$OUT/plots" \
  --json-out "$OUT/report.json" | tee "$OUT/report.txt"
# How many rollers are spalled and how wide (docs/IDENTIFY.md), with the scene's radial load.
LOAD_N=10000
echo "== identify $OUT/run.csv from $FROM s (N205EM, $RPM rpm, $LOAD_N N)"
"$SPALL" identify "$OUT/run.csv" --bearing N205EM --rpm "$RPM" --from-s $FROM --load-n $LOAD_N \
  --json-out "$OUT/identify.json" | tee "$OUT/identify.txt"

RECORD=datasets/samples/n205em_roller_defect_1200rpm.csv
echo "== diagnose $RECORD (N205EM, 1200 rpm)"
"$SPALL" diagnose "$RECORD" --bearing N205EM --rpm 1200 --json-out "$OUT/sample_report.json" |
  tee "$OUT/sample_report.txt"
echo "== wrote $OUT/run.h5, $OUT/report.txt, $OUT/report.json, $OUT/identify.*, $OUT/sample_report.* and $OUT/plots/"
ls "$OUT/plots"
