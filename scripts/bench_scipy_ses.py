#!/usr/bin/python3
"""Reference timing: squared-envelope spectrum (SES) with numpy/scipy, for comparison with
bench/dsp_benchmark (BM_SesOneBand, BM_KurtogramThenSes).

Signal: 10 s at 48 kHz (480,000 samples) of the same kind as the C++ benchmark: impulses at
107.3 Hz with 1 % jitter ringing a 9 kHz resonance (damping 3 %), five shaft harmonics of 29.95 Hz,
white Gaussian noise. Band 7-11 kHz.

Two classic scipy SES recipes are timed, each from the raw record to the one-sided SES:
  fft-mask: rfft, zero outside the band, irfft (band-passed signal), scipy.signal.hilbert,
            |.|^2, mean removed, rfft, |.|/N
  butter:   4th-order Butterworth band-pass with sosfiltfilt, then the same hilbert -> SES
Run with the system interpreter, which has numpy and scipy: /usr/bin/python3 scripts/bench_scipy_ses.py
"""
import argparse
import statistics
import time

import numpy as np
import scipy.signal as sig


def bearing_like_signal(fs=48000.0, seconds=10.0, fault_hz=107.3, jitter=0.01, resonance_hz=9000.0,
                        damping_ratio=0.03, shaft_hz=29.95, shaft_amplitude=0.5, noise_std=0.3,
                        seed=1):
    n = int(round(fs * seconds))
    rng = np.random.default_rng(seed)
    x = np.zeros(n)
    wn = 2 * np.pi * resonance_hz
    decay = damping_ratio * wn
    ring = int(np.ceil(8.0 / decay * fs))
    t_hit = 0.5 / fault_hz
    while True:
        i0 = int(np.ceil(t_hit * fs))
        if i0 >= n:
            break
        m = min(ring, n - i0)
        t = (i0 + np.arange(m)) / fs - t_hit
        x[i0:i0 + m] += np.exp(-decay * t) * np.sin(wn * t)
        t_hit += (1.0 + jitter * rng.standard_normal()) / fault_hz
    t = np.arange(n) / fs
    for h in range(1, 6):
        x += shaft_amplitude / h * np.cos(2 * np.pi * h * shaft_hz * t + h)
    x += noise_std * rng.standard_normal(n)
    return x


def ses_fft_mask(x, fs, band):
    n = x.size
    spec = np.fft.rfft(x)
    f = np.fft.rfftfreq(n, 1 / fs)
    spec[(f < band[0]) | (f > band[1])] = 0
    xb = np.fft.irfft(spec, n)
    se = np.abs(sig.hilbert(xb)) ** 2
    se -= se.mean()
    return np.abs(np.fft.rfft(se)) / n


def ses_butter(x, fs, band):
    sos = sig.butter(4, band, btype="bandpass", fs=fs, output="sos")
    xb = sig.sosfiltfilt(sos, x)
    se = np.abs(sig.hilbert(xb)) ** 2
    se -= se.mean()
    return np.abs(np.fft.rfft(se)) / x.size


def time_it(fn, repeats):
    """Median and minimum wall time, and median process CPU time (comparable with Google
    Benchmark's CPU column when the machine is shared)."""
    wall, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), min(wall), statistics.median(cpu)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    fs, band = 48000.0, (7000.0, 11000.0)
    x = bearing_like_signal(fs=fs)
    ses = ses_fft_mask(x, fs, band)
    alpha = np.fft.rfftfreq(x.size, 1 / fs)
    sel = (alpha > 20) & (alpha < 1000)
    peak = alpha[sel][np.argmax(ses[sel])]
    print(f"signal: {x.size} samples at {fs:.0f} Hz; SES peak {peak:.2f} Hz (fault 107.3 Hz)")
    print(f"numpy {np.__version__}, scipy {__import__('scipy').__version__}")
    for name, fn in (("fft-mask + hilbert", lambda: ses_fft_mask(x, fs, band)),
                     ("butter sosfiltfilt + hilbert", lambda: ses_butter(x, fs, band))):
        fn()  # warm-up
        med, best, cpu = time_it(fn, args.repeats)
        print(f"scipy SES {name:30s} wall median {med * 1e3:6.1f} ms  min {best * 1e3:6.1f} ms"
              f"  cpu median {cpu * 1e3:6.1f} ms")


if __name__ == "__main__":
    main()
