#!/usr/bin/env python3
"""The seeds' validation table (issue 20) from the folders of scripts/validate-methods.sh.

    scripts/validation_table.py OUT      # OUT: validate-methods.sh's output folder

Particle filters: success within 1.5 m and the mean +- SD error over all runs, as seed 001
reports them. Trackers: the mean +- SD distance overhead d_o over the runs that reached the
source box (seed 000 Table 5.x), against the published value, within 25 %, and whether the
measured means keep the published ordering.
"""
import statistics
import sys
from pathlib import Path

from evaluation_runs import read_runs, share_within

PF = [("pf-sweep", "PF + sweeping (0.4, 0.9)", 0.95, 0.79, 0.46),
      ("pf-gradient", "PF + pseudo-gradient (0.2, 0.8)", 0.86, 0.96, 1.01)]
TRACKERS = [("zigzag-15", "zigzag 15°", 1.07), ("surge-cast", "surge-cast", 1.12),
            ("zigzag-30", "zigzag 30°", 1.23), ("gradient-30", "gradient 30°", 1.81),
            ("gradient-60", "gradient 60°", 1.91), ("gradient-90", "gradient 90°", 2.04),
            ("zigzag-60", "zigzag 60°", 2.12), ("zigzag-75", "zigzag 75°", 4.06)]


def mean_sd(xs):
    if not xs:
        return float("nan"), float("nan")
    return statistics.fmean(xs), (statistics.stdev(xs) if len(xs) > 1 else 0.0)


def main(argv):
    if len(argv) != 1:
        sys.exit(__doc__)
    out = Path(argv[0])
    print("| particle filter | runs | success ≤ 1.5 m | error m (mean ± SD) | published | "
          "within 10 points and 0.3 m |")
    print("|---|---|---|---|---|---|")
    for name, label, p_success, p_mean, p_sd in PF:
        if not (out / name / "runs.csv").exists():
            continue
        errors = [float(r["error_m"]) for r in read_runs(out / name)]
        success = share_within(errors)
        m, sd = mean_sd(errors)
        ok = abs(success - p_success) <= 0.10 and abs(m - p_mean) <= 0.3
        print(f"| {label} | {len(errors)} | {100 * success:.0f} % | {m:.2f} ± {sd:.2f} | "
              f"{100 * p_success:.0f} %, {p_mean:.2f} ± {p_sd:.2f} | {'yes' if ok else 'no'} |")
    print()
    print("| tracker | runs | reached box | d_o (mean ± SD) | published | ratio | within 25 % |")
    print("|---|---|---|---|---|---|---|")
    means = []
    for name, label, published in TRACKERS:
        if not (out / name / "runs.csv").exists():
            continue
        rs = read_runs(out / name)
        d = [float(r["distance_overhead"]) for r in rs if r["distance_overhead"]]
        reached = sum(r["reached"] == "1" for r in rs) / len(rs)
        m, sd = mean_sd(d)
        means.append((published, m, label))
        print(f"| {label} | {len(rs)} | {100 * reached:.0f} % | {m:.2f} ± {sd:.2f} | "
              f"{published:.2f} | {m / published:.2f} | "
              f"{'yes' if abs(m / published - 1) <= 0.25 else 'no'} |")
    order = [label for _, _, label in sorted(means, key=lambda t: t[1])]
    published_order = [label for _, _, label in sorted(means, key=lambda t: t[0])]
    print()
    print("Measured ordering: " + " < ".join(order))
    print("Same as published: " + ("yes" if order == published_order else "no"))


if __name__ == "__main__":
    main(sys.argv[1:])
