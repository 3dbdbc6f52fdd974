#!/usr/bin/env python3
"""How far apart in time two defective rollers strike, and how that lag moves during a record
(docs/IDENTIFY.md, "Where the failures lie"): the identification's width step refuses a delay
that lies near the lag at which two counted rollers' impacts correlate, and predicts that lag
as one number from the count's spin phases.

Input: a `spall simulate` output with the rollers' motion (`run.outputs` including "rollers"),
e.g. a case of an identification set simulated again with that output:

    python3 -c "import h5py; print(h5py.File('runs/identify/report/case-00011.h5').attrs['scene'])" > case.toml
    spall simulate case.toml -o case.h5 --set 'run.outputs=["acceleration","rollers"]' --quiet
    python3 scripts/roller_lags.py case.h5 [--from-s 0.05] [--points 10]

For each defective roller (the scene's [[defects]] rollers) the spall's angle from the roller's
outward radius is psi(t) = integral of the spin - orbit angle; the spall meets a race where psi
crosses a multiple of pi, i.e. every half turn of the roller relative to the cage. The lag of
roller b's strikes after roller a's is (psi_a - psi_b) / (2 pi f_rel) modulo the half turn
1 / (2 f_rel), f_rel roller a's mean spin rate relative to the cage. Printed per pair at --points
times, with its range; and each defective roller's mean relative spin rate. Needs numpy and h5py.
"""
import argparse
import sys
import tomllib

import h5py
import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("run_h5")
    p.add_argument("--from-s", type=float, default=0.05, help="leave out the start-up, s")
    p.add_argument("--points", type=int, default=10, help="times at which the lags are printed")
    args = p.parse_args()
    try:
        f = h5py.File(args.run_h5, "r")
    except OSError as e:
        sys.exit(f"{args.run_h5}: cannot open as HDF5 ({e})")
    with f:
        if "rollers" not in f:
            sys.exit(f"{args.run_h5}: no /rollers group (simulate with run.outputs including "
                     "\"rollers\")")
        t = f["time"][:]
        spin = f["rollers/spin"][:]
        orbit = f["rollers/orbit_angle"][:]
        scene = f.attrs["scene"]
        scene = scene.decode() if isinstance(scene, bytes) else scene
    rollers = [d["roller"] for d in tomllib.loads(scene).get("defects", [])]
    if not rollers:
        sys.exit(f"{args.run_h5}: the scene has no defective roller")
    keep = t >= args.from_s
    if keep.sum() < 2:
        sys.exit(f"{args.run_h5}: nothing after --from-s {args.from_s}")
    dt = t[1] - t[0]
    psi = {r: np.cumsum(spin[:, r]) * dt - np.unwrap(orbit[:, r]) for r in rollers}
    rates = {r: abs(np.polyfit(t[keep], psi[r][keep], 1)[0]) / (2 * np.pi) for r in rollers}
    for r in rollers:
        print(f"roller {r}: spin relative to the cage {rates[r]:.4f} Hz")
    half = 0.5 / rates[rollers[0]]
    at = np.linspace(0, keep.sum() - 1, args.points).astype(int)
    for i, a in enumerate(rollers):
        for b in rollers[i + 1:]:
            lag = np.mod((psi[a] - psi[b])[keep] / (2 * np.pi * rates[rollers[0]]), half) * 1e3
            # A lag near 0 or the half turn wraps: report it on the side of its median.
            if np.median(lag) > 0.5 * half * 1e3:
                lag = np.where(lag < 0.25 * half * 1e3, lag + half * 1e3, lag)
            else:
                lag = np.where(lag > 0.75 * half * 1e3, lag - half * 1e3, lag)
            shown = " ".join(f"{v:.2f}" for v in lag[at])
            print(f"rollers {a}-{b}: lag (ms) {shown}; range {lag.min():.2f}-{lag.max():.2f} "
                  f"({lag.max() - lag.min():.2f} ms; half turn {half * 1e3:.2f} ms)")


if __name__ == "__main__":
    main()
