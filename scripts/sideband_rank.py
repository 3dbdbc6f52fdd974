#!/usr/bin/env python3
"""How many cage-angle patterns the count's sideband feature sees in a record (docs/IDENTIFY.md,
"Where the failures lie"): the lines j f_b + m f_c (j = 1..4, |m| <= 4) of the squared envelope
in the diagnosis band, each divided by its noise, as a 4 x 9 matrix. One roller with one
cage-angle pattern makes it rank 1; its singular values say how strong a second pattern is, and
the asymmetry says whether the patterns are symmetric about one cage angle (one roller's are;
two rollers' at different slots are not).

    python3 scripts/sideband_rank.py CASE.h5 [...] --channel /signals/accel_z \\
        --sensor-angle-deg 90 [--spall build/apps/spall]

Each file is a `spall simulate` / `spall dataset run` case (its scene gives speed and load); the
band and the refined rates come from `spall identify --json` of the same record (from 0.05 s).
The lines are measured as `identify/spin_sidebands.h` does (DFT at the exact frequency; noise:
median of the spectrum over +/- 60 bins outside every comb line, / ln 2), approximately: the
squared envelope here is the full-rate analytic signal's. Prints per file the singular values
over the first and the asymmetry: min over a cage angle theta of the sum over j and m > 0 of
|D_jm - D_j,-m|^2 / noise, D_jm = S_jm e^{i m theta}, per real degree of freedom. Needs numpy and
h5py.
"""
import argparse
import json
import subprocess
import sys
import tomllib

import h5py
import numpy as np


def sideband_lines(path, channel, sensor_deg, spall, harmonics=4, orders=4):
    with h5py.File(path, "r") as f:
        scene = f.attrs["scene"]
        scene = scene.decode() if isinstance(scene, bytes) else scene
        x = f[channel][:]
        t = f["time"][:]
    operation = tomllib.loads(scene)["operation"]
    rpm, load = operation["speed_rpm"], operation["radial_load_n"]
    out = subprocess.run([spall, "identify", path, "--bearing", "N205EM", "--rpm", str(rpm),
                          "--channel", channel, "--sensor-angle-deg", str(sensor_deg),
                          "--load-n", str(load), "--from-s", "0.05", "--json"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{path}: spall identify failed: {out.stderr.strip()}")
    d = json.loads(out.stdout)
    if not d["fit"].get("roller_signature"):
        return None
    fc, fb = d["fit"]["cage_hz"], d["fit"]["f_b_hz"]
    band = d["diagnosis"]["band"]
    fs = 1.0 / (t[1] - t[0])
    x = x[t >= 0.05]
    n = len(x) - len(x) % 2
    x = x[:n] - x[:n].mean()
    spec = np.fft.rfft(x)
    freq = np.fft.rfftfreq(n, 1.0 / fs)
    analytic = np.zeros(n, complex)
    keep = (freq >= band["low_hz"]) & (freq <= band["high_hz"])
    analytic[: len(spec)][keep] = 2.0 * spec[keep]
    se = np.abs(np.fft.ifft(analytic)) ** 2
    se -= se.mean()
    power = np.abs(np.fft.rfft(se) / n) ** 2
    df = fs / n
    masked = np.zeros(len(power), bool)
    for j in range(harmonics + 2):
        for m in range(-orders - 2, orders + 3):
            f0 = j * fb + m * fc
            if f0 >= 0:
                c = int(round(f0 / df))
                masked[max(0, c - 2): c + 3] = True
    tt = np.arange(n) / fs
    value = np.zeros((harmonics, 2 * orders + 1), complex)
    noise = np.zeros(value.shape)
    for j in range(1, harmonics + 1):
        for m in range(-orders, orders + 1):
            f0 = j * fb + m * fc
            value[j - 1, m + orders] = np.sum(se * np.exp(-2j * np.pi * f0 * tt)) / n
            c = int(round(f0 / df))
            window = [power[b] for b in range(max(1, c - 60), min(len(power), c + 61))
                      if not masked[b]]
            noise[j - 1, m + orders] = np.median(window) / np.log(2.0)
    return value, noise


def asymmetry(value, noise):
    harmonics, lines = value.shape
    orders = (lines - 1) // 2
    best = np.inf
    for theta in np.linspace(-np.pi, np.pi, 721):
        d = value * np.exp(1j * np.arange(-orders, orders + 1) * theta)[None, :]
        a = 0.0
        for m in range(1, orders + 1):
            a += np.sum(np.abs(d[:, orders + m] - d[:, orders - m]) ** 2 /
                        (0.5 * (noise[:, orders + m] + noise[:, orders - m])))
        best = min(best, a)
    return best / (2 * harmonics * orders)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("files", nargs="+")
    p.add_argument("--channel", default="/signals/accel_z")
    p.add_argument("--sensor-angle-deg", type=float, default=90.0)
    p.add_argument("--spall", default="build/apps/spall")
    args = p.parse_args()
    for path in args.files:
        lines = sideband_lines(path, args.channel, args.sensor_angle_deg, args.spall)
        if lines is None:
            print(f"{path}: no roller signature")
            continue
        value, noise = lines
        s = np.linalg.svd(value / np.sqrt(0.5 * noise), compute_uv=False)
        print(f"{path}: singular values / first " + " ".join(f"{v / s[0]:.2f}" for v in s) +
              f"; asymmetry {asymmetry(value, noise):.2f}")


if __name__ == "__main__":
    main()
