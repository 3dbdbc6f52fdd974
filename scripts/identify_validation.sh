#!/usr/bin/env bash
# The identification's validation on simulated records (docs/IDENTIFY.md, "Validation on
# simulated records") in one command: generates the six lumped-model sets of datasets/sweeps/identify-*.toml
# (lumped model; `spall dataset run` resumes a folder it finds part-done), runs `spall
# identify-check` on each at clean, 10 and 0 dB (horizontal channel, the scene's load given) and
# prints one table of counts right / wrong / refused and widths stated / within 15 %, and one by
# class of the true width.
#
#   bash scripts/identify_validation.sh [OUT_DIR]      (default runs/identify)
#
# Extra `spall identify-check` options pass through SPALLKIT_CHECK_ARGS, e.g.
# SPALLKIT_CHECK_ARGS="--width-max-count 1". SPALLKIT_LUBRICATED=1 makes the sets with the
# main job's lubricant traction law and film on the races instead of the sets' dry Coulomb
# 0.15 / 0.12 (pockets at the scene's 0.01 / 0.005; docs/IDENTIFY.md, "Sets with lubricant
# traction"): the sweep files are copied to OUT with that change. SPALLKIT_BASE_SET adds one
# line to every sweep's [base.set] (copied likewise), e.g.
# SPALLKIT_BASE_SET='"bearing.cage_radial_play_mm" = 0.1' (docs/BEARING_MODEL.md, "Cage radial
# play"). About 8 min of generation and 3 min of checks on 2 cores (both run one file per
# core). Uses build/apps/spall
# (SPALLKIT_SPALL overrides).
set -euo pipefail
cd "$(dirname "$0")/.."
SPALL=${SPALLKIT_SPALL:-build/apps/spall}
OUT=${1:-runs/identify}
SETS="report report-long tune width width-multi width-three"
WORKERS=$(nproc)
mkdir -p "$OUT"
# A sweep file copied to OUT names its scene by absolute path (the sweep's is relative to it).
absolute_scene() { sed -e "s|^scene = \"\.\./scenes/|scene = \"$PWD/datasets/scenes/|" "$1"; }
for set in $SETS; do
  echo "== generate identify-$set ($OUT/$set)" >&2
  sweep="datasets/sweeps/identify-$set.toml"
  if [ "${SPALLKIT_LUBRICATED:-0}" = 1 ]; then
    lubricated="$OUT/identify-$set-lubricated.toml"
    absolute_scene "$sweep" | sed -e '/^"friction.mu_static" = 0.15$/d' \
      -e 's|^"friction.mu_dynamic" = 0.12$|"friction.model" = "ehl"|' >"$lubricated"
    grep -q '^"friction.model" = "ehl"$' "$lubricated" ||
      { echo "identify_validation.sh: $sweep has no friction lines to replace" >&2; exit 2; }
    sweep="$lubricated"
  fi
  if [ -n "${SPALLKIT_BASE_SET:-}" ]; then
    with_set="$OUT/identify-$set-base-set.toml"
    absolute_scene "$sweep" | awk -v line="$SPALLKIT_BASE_SET" '
      { print }
      /^\[base\.set\]$/ { print line; added = 1 }
      END { if (!added) exit 3 }' >"$with_set" ||
      { echo "identify_validation.sh: $sweep has no [base.set] table" >&2; exit 2; }
    sweep="$with_set"
  fi
  "$SPALL" dataset run "$sweep" --out "$OUT/$set" \
    --workers "$WORKERS" >"$OUT/$set.generate.txt"
done
for set in $SETS; do
  echo "== check identify-$set" >&2
  # shellcheck disable=SC2086  # the extra arguments are words
  "$SPALL" identify-check "$OUT/$set" --channel /signals/accel_z --sensor-angle-deg 90 \
    --snr-db inf,10,0 --workers "$WORKERS" --csv "$OUT/$set.csv" ${SPALLKIT_CHECK_ARGS:-} \
    >"$OUT/$set.check.txt"
done
printf '%-12s %-6s %-22s %s\n' set SNR "count right/wrong/ref" "widths stated (within 15 %)"
for set in $SETS; do
  awk -v set="$set" '
    /^SNR / { snr = $2; sub(":", "", snr) }
    /^ *spalled records:/ {
      match($0, /count right [0-9]+/); right = substr($0, RSTART + 12, RLENGTH - 12)
      match($0, /wrong [0-9]+/); wrong = substr($0, RSTART + 6, RLENGTH - 6)
      match($0, /refused [0-9]+/); refused = substr($0, RSTART + 8, RLENGTH - 8)
      match($0, /spalled records: [0-9]+/); spalled = substr($0, RSTART + 17, RLENGTH - 17)
    }
    /width stated on/ {
      stated = $4; within = 0
      if (match($0, /within 15 % [0-9]+/)) within = substr($0, RSTART + 12, RLENGTH - 12)
      printf "%-12s %-6s %-22s %s of %s (%s)\n", set, snr, right "/" wrong "/" refused, stated,
             spalled, within
    }' "$OUT/$set.check.txt"
done
# The same per class of the true width, the three SNRs summed (docs/IDENTIFY.md, "Where the
# failures lie"): spalled record-SNR pairs; no roller signature, counts right, widths within 15 %.
printf '\n%-12s %-12s %s\n' set "width (mm)" "spalled; no roller signature, count right, width within 15 %"
for set in $SETS; do
  awk -v set="$set" '
    /by true width/ {
      line = $0
      while (match(line, /\[[0-9.]+-[0-9.]+\) mm: [0-9]+; [0-9]+, [0-9]+, [0-9]+;/)) {
        item = substr(line, RSTART, RLENGTH); line = substr(line, RSTART + RLENGTH)
        split(item, f, /[][ ;,)]+/)
        cls = f[2]; n[cls] += f[4]; ns[cls] += f[5]; r[cls] += f[6]; w[cls] += f[7]
        if (!(cls in seen)) { seen[cls] = 1; order[++k] = cls }
      }
    }
    END { for (i = 1; i <= k; ++i) { c = order[i]
            printf "%-12s %-12s %d; %d, %d, %d\n", set, c, n[c], ns[c], r[c], w[c] } }' \
    "$OUT/$set.check.txt"
done
