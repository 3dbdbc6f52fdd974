#!/usr/bin/env python3
"""The paper's parametric study in one command (datasets/sweeps/paper-study.toml, docs/PAPER.md).

For each [[part]] of the study file: runs its `spall dataset` sweep file (`sweep`, relative to the
study file) with `spall dataset run` into OUT/<part> (resumable: run the command again to finish a
killed study),
then `spall plot study` for each quantity of [plots] (OUT/<part>-<quantity>.png and .csv), and
finally OUT/summary.md: one table per part, a row per case, a column per quantity.
Python standard library only.
"""
import argparse
import csv
import os
import subprocess
import sys
import tomllib


def quantity_file_name(q):
    return q.replace("rms:/", "rms-").replace("/", "-")


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", nargs="?", default=os.path.join(root, "datasets/sweeps/paper-study.toml"))
    ap.add_argument("--out", default="runs/paper-study")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--spall", default=os.path.join(root, "build/apps/spall"))
    ap.add_argument("--parts", default="", help="comma-separated part names (default: all)")
    a = ap.parse_args()
    try:
        with open(a.study, "rb") as f:
            study = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        print(f"paper_study: {a.study}: {e}", file=sys.stderr)
        return 2
    here = os.path.dirname(os.path.abspath(a.study))
    parts = study.get("part", [])
    wanted = [p for p in a.parts.split(",") if p]
    plots = study.get("plots", {})
    from_s = float(plots.get("from_s", 0.0))
    quantities = plots.get("quantities", ["accel_rms"])
    summary = []
    for part in parts:
        name = part["name"]
        if wanted and name not in wanted:
            continue
        out = os.path.join(a.out, name)
        os.makedirs(out, exist_ok=True)
        sweep = os.path.normpath(os.path.join(here, part["sweep"]))
        print(f"== {name}: {a.spall} dataset run {sweep} --out {out}", flush=True)
        rc = subprocess.run([a.spall, "dataset", "run", sweep, "--out", out,
                             "--workers", str(a.workers)]).returncode
        if rc != 0:
            print(f"paper_study: part {name}: spall dataset run failed ({rc})", file=sys.stderr)
            return rc
        table = {}
        for q in quantities:
            base = os.path.join(a.out, f"{name}-{quantity_file_name(q)}")
            rc = subprocess.run([a.spall, "plot", "study", out, "--x", part["x"], "--y", q,
                                 "--one-line", "--from-s", str(from_s), "-o", base + ".png",
                                 "--csv", base + ".csv"]).returncode
            if rc != 0:
                print(f"paper_study: part {name}: plot of {q} failed ({rc})", file=sys.stderr)
                return rc
            with open(base + ".csv") as f:
                for row in csv.DictReader(f):
                    table.setdefault(float(row[part["x"]]), {})[q] = float(row[q])
        summary.append(f"### {name}\n\n| {part['x']} | " + " | ".join(quantities) + " |")
        summary.append("|---" * (len(quantities) + 1) + "|")
        for x in sorted(table):
            cells = [f"{table[x][q]:.3g}" if q in table[x] else "-" for q in quantities]
            summary.append(f"| {x:g} | " + " | ".join(cells) + " |")
        summary.append("")
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(summary) + "\n")
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
