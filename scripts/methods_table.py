#!/usr/bin/env python3
"""A Markdown table of `evaluate` summaries side by side (issue 20's comparison).

    scripts/methods_table.py DIR...      # each DIR an `evaluate --out` folder

One row per folder: the method (STE with its plume model), runs, success within 0.5 m and 1 m
with their 95 % intervals, within 1.5 m (the seeds' criterion), median error, samples, distance
and mission time, the field's time metrics (issue 47: median time to come within 1 m of the
source, the median mission over the shortest way's time, GSL-Bench's 1 m within 300 s; "–" for a
summary made before them), the median decision step, and for the methods other than STE the
share that reached the source box and the median distance overhead.
"""
import json
import sys
from pathlib import Path

from evaluation_runs import read_runs, share_within


def pct(x):
    return f"{100 * x:.0f} %"


def ci(pair):
    return f"({100 * pair[0]:.0f}–{100 * pair[1]:.0f})"


def number(value, spec, unit=""):
    return "–" if value is None else f"{value:{spec}}{unit}"


def times(o):
    gsl = o.get("gsl_bench_success")
    return (f"{number(o.get('median_time_to_1m_s'), '.0f')} | "
            f"{number(o.get('median_mission_over_optimum'), '.1f')} | "
            f"{'–' if gsl is None else pct(gsl)}")


def row(folder):
    s = json.loads((Path(folder) / "summary.json").read_text())
    t = json.loads((Path(folder) / "timings.json").read_text())
    o = s["overall"]
    method = s.get("method", "ste")
    name = f"ste ({s['plume_model']})" if method == "ste" else method
    reached = pct(o["reached_source_box"]) if "reached_source_box" in o else "–"
    overhead = o.get("median_distance_overhead")
    within_1_5 = share_within([float(r["error_m"]) for r in read_runs(folder)])
    return (f"| {name} | {o['runs']} | {pct(o['success_0_5m'])} {ci(o['success_0_5m_ci95'])} | "
            f"{pct(o['success_1_0m'])} {ci(o['success_1_0m_ci95'])} | {pct(within_1_5)} | "
            f"{o['median_error_m']:.2f} | "
            f"{o['median_samples']:.0f} | {o['median_distance_m']:.1f} | "
            f"{o['median_mission_s']:.0f} | {times(o)} | "
            f"{1000 * t['median_step_compute_s']:.2f} | {reached} | "
            f"{'–' if overhead is None else f'{overhead:.2f}'} |")


def main(folders):
    if not folders:
        sys.exit(__doc__)
    print("| method | runs | within 0.5 m | within 1 m | within 1.5 m | median error m | samples "
          "| distance m | mission s | to 1 m s | mission ÷ optimum | GSL 1 m in 300 s | step ms "
          "| reached box | distance overhead |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for f in folders:
        print(row(f))


if __name__ == "__main__":
    main(sys.argv[1:])
