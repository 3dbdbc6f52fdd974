#!/usr/bin/env python3
"""Cyclic-spectral evidence on the measured records (docs/DIAGNOSIS.md, "Rolling-element faults"):
does an improved envelope spectrum (IES) from the spectral coherence show the ball-fault comb
where the squared envelope spectrum does not?

For each record of a manifest folder (the format of ../shared/data/measured/manifest.json) the
cyclic modulation spectrum is computed from a short-time Fourier transform (Hann window of
--window samples, hop --hop): for every spectral bin f the spectrum of |X(t, f)|^2 over t,
normalised by its mean, i.e. the spectral coherence |gamma(alpha, f)| (Antoni 2009, Borghesani
et al. 2014). The IES is its mean over a band of f. For each record's own fault family (ball:
2 x BSF and 4 x BSF, i.e. f_b and 2 f_b; outer race: BPFO and 2 BPFO; inner race: BPFI and 2 BPFI;
healthy: the ball family) the statistic is the weaker of the two lines' prominence (largest IES
value within +/- 2 % of the kinematic frequency over the median within +/- 15 Hz outside it), in
the whole band (200 Hz to 0.48 fs) and in the best of the octave-like bands searched. The same
statistic at 40 decoy frequencies (the family scaled by 1.1-1.5, where no bearing family lies
for these geometries) gives each record's own null distribution: the fraction of decoys at or
above the family's value is the empirical p-value of the search.

    python3 scripts/ies_check.py ../shared/data/measured [--window 64 --hop 8]

Needs numpy, scipy and pandas (scripts/install-deps.sh installs them). About 10 s.
"""
import argparse
import json
import os
import sys

import numpy as np
import pandas as pd
from scipy import signal

FAMILY = {"ball": "BSFx2", "normal": "BSFx2", "inner_race": "BPFI"}


def coherence(x, fs, window, hop):
    """(alpha, f, |gamma(alpha, f)|) of the cyclic modulation spectrum."""
    w = np.hanning(window)
    frames = (len(x) - window) // hop + 1
    idx = np.arange(window)[None, :] + hop * np.arange(frames)[:, None]
    power = np.abs(np.fft.rfft(x[idx] * w, axis=1)) ** 2
    mean = power.mean(0)
    gamma = np.abs(np.fft.rfft(power - mean, axis=0)) / (mean * frames)
    return np.fft.rfftfreq(frames, hop / fs), np.fft.rfftfreq(window, 1 / fs), gamma


def prominence(alpha, ies, f0, tol=0.02, half=15.0):
    inside = (alpha > f0 * (1 - tol)) & (alpha < f0 * (1 + tol))
    around = (np.abs(alpha - f0) < half) & ~inside
    return ies[inside].max() / np.median(ies[around])


def band_ies(f, gamma, bands):
    """The IES of each band: the coherence's mean over the band's spectral bins."""
    return [gamma[:, (f >= lo) & (f <= hi)].mean(1) for lo, hi in bands]


def family_score(alpha, ies_per_band, f0):
    """Weaker of the two harmonics' prominence: whole band (the first), and the best band."""
    scores = [min(prominence(alpha, ies, f0), prominence(alpha, ies, 2 * f0)) for ies in ies_per_band]
    return scores[0], max(scores[1:])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("folder")
    p.add_argument("--manifest", default="manifest.json")
    p.add_argument("--window", type=int, default=64)
    p.add_argument("--hop", type=int, default=8)
    args = p.parse_args()
    path = os.path.join(args.folder, args.manifest)
    try:
        records = json.load(open(path))
    except (OSError, ValueError) as e:
        sys.exit(f"{path}: {e}")
    rng = np.random.default_rng(1)
    decoy_scale = rng.uniform(1.1, 1.5, 40)
    rows = []
    for r in records:
        freqs = r.get("char_freq_hz_at_file_rpm")
        if not freqs:  # MFPT: no kinematic table in the manifest; race faults only
            continue
        fault = r["fault"]
        key = FAMILY.get(fault, "BPFO" if fault.startswith("outer") else None)
        x = pd.read_csv(os.path.join(args.folder, r["file"])).iloc[:, 1].to_numpy(float)
        x -= x.mean()
        fs = r["fs_hz"]
        if fs > 20000:  # the 48 kHz healthy record at the fault records' 12 kHz
            x = signal.decimate(x, int(round(fs / 12000)))
            fs = 12000
        f0 = freqs[key]
        needed = 2 * 1.5 * f0 * 1.02 + 15.0  # the decoys' second harmonic and its surroundings
        if needed > fs / (2 * args.hop):
            sys.exit(f"--hop {args.hop}: {r['file']} needs cyclic frequencies up to {needed:.0f} Hz, "
                     f"a hop of {args.hop} samples at {fs:g} Hz reaches {fs / (2 * args.hop):.0f} Hz")
        alpha, f, gamma = coherence(x, fs, args.window, args.hop)
        top = 0.48 * fs
        bands = [(200.0, top)]
        for width in (top / 8, top / 4, top / 2):
            bands += [(lo, lo + width) for lo in np.arange(0.0, top - width + 1, width / 2)]
        ies = band_ies(f, gamma, bands)
        whole, best = family_score(alpha, ies, f0)
        decoys = np.array([family_score(alpha, ies, f0 * s)[1] for s in decoy_scale])
        rows.append({"record": r["file"].split("_DE")[0], "fault": fault, "family": key,
                     "whole band": round(whole, 1), "best band": round(best, 1),
                     "decoys median": round(float(np.median(decoys)), 1),
                     "p (decoys >= best)": round(float((decoys >= best).mean()), 3)})
    pd.set_option("display.width", 200)
    print(pd.DataFrame(rows).to_string(index=False))


if __name__ == "__main__":
    main()
