#!/usr/bin/python3
"""The table of seed 004 ch. 16's benchmark from scripts/levy-benchmark.sh's output.

    scripts/levy_table.py OUT

For each condition (A-D) and start (plume, crosswind), and each method: the runs, the successes
(entered 0.5 m of the source; for STE also a declaration within 0.5 m, ch. 15), and the median
and quartiles of the travelled distance over all runs (the thesis's metric). Exit 2 when a
folder is missing or a runs.csv is malformed.
"""
import os
import statistics
import sys

from evaluation_runs import read_runs

CONDITIONS = [("A", "0.2 m/s, 5 %"), ("B", "0.2 m/s, 10 %"), ("C", "0.9 m/s, 5 %"),
              ("D", "0.9 m/s, 10 %")]
METHODS = ["ste", "levy-taxis"]


def fail(message):
    print(f"levy_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def quartiles(values):
    q = statistics.quantiles(values, n=4, method="inclusive") if len(values) > 1 else values * 3
    return q[0], statistics.median(values), q[2]


def row(path):
    try:
        runs = read_runs(path)
        distance = [float(r["distance_m"]) for r in runs]
        ok = sum(r["stopped_by"] == "reached" or
                 (r["stopped_by"] == "entropy" and float(r["error_m"]) <= 0.5) for r in runs)
    except (OSError, KeyError, ValueError) as e:
        fail(f"{path}: {e}")
    if not runs:
        fail(f"{path}: no runs")
    lo, mid, hi = quartiles(distance)
    return len(runs), ok, lo, mid, hi


def main(argv):
    if len(argv) != 2:
        fail("usage: levy_table.py OUT")
    out = argv[1]
    print("| condition | start | method | runs | success | distance m: median (quartiles) |")
    print("|---|---|---|---|---|---|")
    for name, what in CONDITIONS:
        for start in ("plume", "crosswind"):
            for method in METHODS:
                n, ok, lo, mid, hi = row(os.path.join(out, f"{name}-{start}", method))
                print(f"| {name} ({what}) | {start} | {method} | {n} | {100 * ok / n:.0f} % | "
                      f"{mid:.1f} ({lo:.1f}–{hi:.1f}) |")


if __name__ == "__main__":
    main(sys.argv)
