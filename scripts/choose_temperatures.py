#!/usr/bin/env python3
"""Chooses the count fit's temperatures (CountFitOptions::temperature_cage / _sidebands) on a
tuning set, as docs/IDENTIFY.md ("Temperatures") describes: the pair that maximises the mean log
probability of the true defective-roller count over the records with a roller signature, from
the per-K log evidences that `spall identify-check --csv` writes.

    spall identify-check runs/identify/tune --channel /signals/accel_z --sensor-angle-deg 90 \\
        --snr-db inf,10,0 --csv tune.csv
    python3 scripts/choose_temperatures.py tune.csv [--check report.csv] [--max-confident-wrong 0]
    python3 scripts/choose_temperatures.py --ranks tune.csv report.csv ...

--check prints the same score on another set (e.g. the report set) at the chosen pair and at
the current defaults, without using it for the choice. Needs numpy.
"""
import argparse
import csv
import math
import sys

import numpy as np

CURRENT = (5.0, 28.0)  # identify/count_fit.h
GRID = list(range(1, 10)) + list(range(10, 60, 2)) + list(range(60, 201, 5))


def load(path):
    """(true count, ln Z_A per K, ln Z_B per K) of every row with a roller signature."""
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if not r["log_evidence_cage"]:
                continue
            a = np.array([float(x) for x in r["log_evidence_cage"].split(";") if x])
            b = np.array([float(x) for x in r["log_evidence_sidebands"].split(";") if x])
            rows.append((int(r["true_count"]), a, b))
    if not rows:
        sys.exit(f"{path}: no row with log evidences (run spall identify-check with --csv)")
    return rows


def log_probabilities(a, b, t_a, t_b):
    """ln P(K) per K, P(K) proportional to exp(ln Z_A / t_a + ln Z_B / t_b)."""
    z = a / t_a + b / t_b
    finite = z[np.isfinite(z)]
    top = finite.max()
    return z - (top + math.log(np.exp(finite - top).sum()))


def most_probable(v):
    """The K of the largest finite entry of a per-K log evidence or log probability."""
    return int(np.argmax(np.where(np.isfinite(v), v, -np.inf)))


def mean_log_p(rows, t_a, t_b, floor=-50.0):
    """Mean ln P(true K) over the rows."""
    total = 0.0
    for k, a, b in rows:
        lp = log_probabilities(a, b, t_a, t_b)
        total += max(lp[k] if k < len(lp) and np.isfinite(lp[k]) else floor, floor)
    return total / len(rows)


def confident_wrong(rows, t_a, t_b, level=0.99):
    """Records whose most probable count is not the true one, at P >= level."""
    n = 0
    for k, a, b in rows:
        lp = log_probabilities(a, b, t_a, t_b)
        best = most_probable(lp)
        if best != k and best > 0 and math.exp(lp[best]) >= level:
            n += 1
    return n


def first_ranked(rows, t_a, t_b, level=0.6):
    """Records whose most probable count is the true one: feature A alone, B alone, both at
    (t_a, t_b) per K; and of both, the right / wrong ones at P >= level."""
    a_right = b_right = both_right = sure_right = sure_wrong = 0
    for k, a, b in rows:
        a_right += most_probable(a) == k
        b_right += most_probable(b) == k
        lp = log_probabilities(a, b, t_a, t_b)
        best = most_probable(lp)
        both_right += best == k
        if math.exp(lp[best]) >= level:
            sure_right += best == k
            sure_wrong += best != k
    return a_right, b_right, both_right, sure_right, sure_wrong


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("tune_csv")
    p.add_argument("--check", help="another set's CSV, scored but not used for the choice")
    p.add_argument("--max-confident-wrong", type=int, default=None,
                   help="only pairs with at most this many wrong counts at P >= 0.99 on the "
                        "tuning set (the defaults: 0)")
    p.add_argument("--ranks", action="store_true",
                   help="instead of choosing: for each CSV, how often the most probable count is "
                        "the true one (feature A alone, B alone, both at the current temperatures) "
                        "and how many of both's are right / wrong at P >= 0.6")
    p.add_argument("more_csv", nargs="*", help="with --ranks: further CSV files")
    args = p.parse_args()
    if args.ranks:
        print("file: records with a roller signature; most probable count right with A alone, "
              "B alone, both; both at P >= 0.6 right / wrong")
        for path in [args.tune_csv] + args.more_csv:
            rows = load(path)
            a, b, both, right, wrong = first_ranked(rows, *CURRENT)
            print(f"{path}: {len(rows)}; {a}, {b}, {both}; {right} / {wrong}")
        return
    tune = load(args.tune_csv)
    pairs = [(a, b) for a in GRID for b in GRID]
    if args.max_confident_wrong is not None:
        pairs = [(a, b) for a, b in pairs
                 if confident_wrong(tune, a, b) <= args.max_confident_wrong]
    best = max((mean_log_p(tune, a, b), a, b) for a, b in pairs)
    print(f"tuning set: {len(tune)} records with a roller signature")
    print(f"chosen: T_A {best[1]}, T_B {best[2]}: mean ln P(true K) {best[0]:.3f} "
          f"(current {CURRENT[0]:g}, {CURRENT[1]:g}: {mean_log_p(tune, *CURRENT):.3f})")
    if args.check:
        other = load(args.check)
        print(f"check set: {len(other)} records; chosen {mean_log_p(other, best[1], best[2]):.3f}, "
              f"current {mean_log_p(other, *CURRENT):.3f}; wrong at P >= 0.99: chosen "
              f"{confident_wrong(other, best[1], best[2])}, current "
              f"{confident_wrong(other, *CURRENT)}")


if __name__ == "__main__":
    main()
